// Mirrors adapt/transient_loop.hpp on a CI-sized moving peak (a few seconds): the adaptive run's
// space-time error is well below the uniform mesh's at the same average vertex count, every
// transfer conserves mass, the interval metric keeps the error bounded where the metric of the
// current solution lets it grow, the run is bitwise the same on 1 and 2 threads, and bad options
// are InputErrors naming the option.
#include "ablmg/adapt/transient_loop.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {

/// A wide peak on a short interval: 30 steps, 6 intervals, 600-vertex meshes.
fem::TransientProblem smallPeak() { return fem::makeTransientProblem("movingpeak", {{"alpha", 300}}); }

TransientOptions smallOptions() {
  TransientOptions o;
  o.dt = 0.004;
  o.tEnd = 0.12;
  o.remeshEvery = 5;
  o.vertices = 600;
  o.fixedPointIterations = 1;
  return o;
}

const TransientReport& adaptiveRun() {
  static const TransientReport r = runTransientLoop(smallPeak(), smallOptions());
  return r;
}

}  // namespace

TEST(TransientLoop, AdaptiveBeatsUniformAtTheSameAverageVertexCount) {
  const TransientReport& a = adaptiveRun();
  TransientOptions o = smallOptions();
  o.uniform = true;
  o.vertices = a.averageVertices;
  const TransientReport u = runTransientLoop(smallPeak(), o);
  EXPECT_NEAR(u.averageVertices, a.averageVertices, 0.1 * a.averageVertices);
  EXPECT_EQ(a.steps.size(), 30u);
  EXPECT_EQ(a.intervals.size(), 6u);
  EXPECT_LT(a.spaceTimeL2, u.spaceTimeL2 / 3) << "adaptive " << a.spaceTimeL2 << ", uniform " << u.spaceTimeL2;
  EXPECT_LT(a.spaceTimeH1, u.spaceTimeH1 / 1.5);
  EXPECT_EQ(u.meshes, 1);
  EXPECT_EQ(a.meshes, 1 + 6);  // the initial mesh, then one remesh per fixed-point pass
}

TEST(TransientLoop, TransfersConserveMass) {
  const TransientReport& a = adaptiveRun();
  EXPECT_LT(a.maxMassDefect, 1e-12);
  for (const auto& rec : a.intervals) EXPECT_LT(rec.massDefect, 1e-12) << "interval " << rec.interval;
}

TEST(TransientLoop, IntervalMetricKeepsTheErrorBoundedBetweenRemeshes) {
  const TransientReport& a = adaptiveRun();
  TransientOptions o = smallOptions();
  o.metric = TransientMetric::Current;
  const TransientReport c = runTransientLoop(smallPeak(), o);
  EXPECT_LT(a.maxL2, c.maxL2);
  EXPECT_LT(a.spaceTimeL2, c.spaceTimeL2);
}

TEST(TransientLoop, SameBitsOnOneAndTwoThreads) {
  TransientOptions o = smallOptions();
  o.tEnd = 0.02;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const TransientReport one = runTransientLoop(smallPeak(), o);
  omp_set_num_threads(2);
  const TransientReport two = runTransientLoop(smallPeak(), o);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.steps.size(), two.steps.size());
  for (std::size_t n = 0; n < one.steps.size(); ++n) {
    EXPECT_EQ(one.steps[n].vertices, two.steps[n].vertices);
    EXPECT_EQ(one.steps[n].l2, two.steps[n].l2);
  }
}

TEST(TransientLoop, BadOptionsAreInputErrorsNamingTheOption) {
  const auto message = [](TransientOptions o) {
    try {
      runTransientLoop(smallPeak(), o);
    } catch (const InputError& e) { return std::string(e.what()); }
    return std::string("no error");
  };
  TransientOptions o = smallOptions();
  o.remeshEvery = 0;
  EXPECT_NE(message(o).find("remeshEvery must be >= 1"), std::string::npos) << message(o);
  o = smallOptions();
  o.dt = -0.1;
  EXPECT_NE(message(o).find("dt must be > 0"), std::string::npos) << message(o);
  o = smallOptions();
  o.hessianEvery = 0;
  EXPECT_NE(message(o).find("hessianEvery must be >= 1"), std::string::npos) << message(o);
  o = smallOptions();
  o.tEnd = -1;
  EXPECT_NE(message(o).find("must be after the start time"), std::string::npos) << message(o);
}
