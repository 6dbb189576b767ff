// Mirrors adapt/metric_snap.hpp: snapped tensors are SPD and within the stated size change,
// round-off-level differences (including a flipped sign of m12 at θ = π/2) give the same bits,
// isotropic tensors stay exactly isotropic, and RemeshOptions::metricQuantum makes a remesh of
// a metric perturbed by 1e-11 give the same mesh, which it does not without.
#include "ablmg/adapt/metric_snap.hpp"

#include "ablmg/adapt/remesh.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace ablmg;

namespace {
constexpr double kQuantum = 0x1.0p-8;

bool sameBits(const Metric2& a, const Metric2& b) {
  return a.m11() == b.m11() && a.m12() == b.m12() && a.m22() == b.m22();
}
}  // namespace

TEST(MetricSnap, SizesMoveLessThanTheBoundAndRoundOffIsAbsorbed) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> logh(std::log(1e-4), std::log(1.0)), angle(-3.2, 3.2), unit(-1, 1);
  int same = 0, trials = 2000;
  for (int t = 0; t < trials; ++t) {
    const double h1 = std::exp(logh(rng)), h2 = h1 * std::exp(unit(rng) * std::log(10.0));  // anisotropy ≤ 10
    const Metric2 m = Metric2::fromSizes(h1, h2, angle(rng));
    const Metric2 s = adapt::snapMetric(m, kQuantum);
    ASSERT_TRUE(s.isSpd());
    const MetricEigen a = m.eigen(), b = s.eigen();
    const double bound = kQuantum * std::numbers::ln2 / 4 * 1.0001 + 1e-12;
    EXPECT_LE(std::abs(std::log(std::max(b.h1, b.h2) / std::max(a.h1, a.h2))), bound);
    EXPECT_LE(std::abs(std::log(std::min(b.h1, b.h2) / std::min(a.h1, a.h2))), bound);
    const Metric2 p = Metric2::raw(m.m11() * (1 + 1e-11 * unit(rng)), m.m12() * (1 + 1e-11 * unit(rng)),
                                   m.m22() * (1 + 1e-11 * unit(rng)));
    same += sameBits(adapt::snapMetric(p, kQuantum), s);
  }
  // A straddle of a grid boundary is possible but rare (anisotropy ≤ 10 here: ≲ 1e-6 each).
  EXPECT_GE(same, trials - 2);
}

TEST(MetricSnap, AxisAlignedSignFlipAndIsotropyGiveOneTensor) {
  // Principal axis along y (θ = π/2): m12 = ±1e-20 are the same tensor up to round-off.
  const Metric2 plus = Metric2::raw(1.0, 1e-20, 100.0), minus = Metric2::raw(1.0, -1e-20, 100.0);
  EXPECT_TRUE(sameBits(adapt::snapMetric(plus, kQuantum), adapt::snapMetric(minus, kQuantum)));
  const Metric2 iso = adapt::snapMetric(Metric2::raw(4.0 * (1 + 1e-13), 1e-15, 4.0), kQuantum);
  EXPECT_EQ(iso.m12(), 0.0);
  EXPECT_EQ(iso.m11(), iso.m22());
  std::vector<Metric2> v{plus};
  EXPECT_THROW(adapt::snapMetrics(v, 0.0), InputError);
  EXPECT_THROW(adapt::snapMetrics(v, std::nan("")), InputError);
}

TEST(MetricSnap, RemeshOfAPerturbedMetricGivesTheSameMesh) {
  const Mesh2 in = fem::unitSquareMesh(12, 0.1, 3);
  std::vector<Metric2> metric, perturbed;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const Vec2& p : in.vertices) {
    const double h = 0.02 + 0.1 * std::abs(p.x() - 0.5);  // graded along x
    metric.push_back(Metric2::fromSizes(h, 2 * h, 0.3));
    const Metric2& m = metric.back();
    perturbed.push_back(Metric2::raw(m.m11() * (1 + 1e-11 * unit(rng)), m.m12() * (1 + 1e-11 * unit(rng)),
                                     m.m22() * (1 + 1e-11 * unit(rng))));
  }
  adapt::RemeshOptions o;
  const auto a = adapt::remesh(in, metric, o), b = adapt::remesh(in, perturbed, o);
  EXPECT_NE(a.mesh.vertices, b.mesh.vertices);  // the placement is chaotic in its input
  o.metricQuantum = kQuantum;
  const auto c = adapt::remesh(in, metric, o), d = adapt::remesh(in, perturbed, o);
  EXPECT_EQ(c.mesh.vertices, d.mesh.vertices);
  EXPECT_EQ(c.mesh.triangles, d.mesh.triangles);
  EXPECT_TRUE(c.mesh.validate().ok);
  EXPECT_NEAR(double(c.mesh.numVertices()), double(a.mesh.numVertices()), 0.02 * a.mesh.numVertices());
  o.metricQuantum = -1;
  EXPECT_THROW(adapt::remesh(in, metric, o), InputError);
}
