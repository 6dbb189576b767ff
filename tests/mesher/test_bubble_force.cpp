#include "ablmg/mesher/bubble_force.hpp"

#include "ablmg/core/domain.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace ablmg;
using namespace ablmg::mesher;

TEST(BubbleForce, Eq7KnownValues) {
  EXPECT_DOUBLE_EQ(interBubbleForce(0.0), 1.125);
  EXPECT_NEAR(interBubbleForce(1.0), 0.0, 1e-15);
  EXPECT_NEAR(interBubbleForce(1.5), 0.0, 1e-15);
  EXPECT_EQ(interBubbleForce(1.6), 0.0);
  EXPECT_EQ(interBubbleForce(-0.1), 0.0);
  EXPECT_DOUBLE_EQ(interBubbleForce(0.5, 2.0), 2.0 * (1.25 * 0.125 - 2.375 * 0.25 + 1.125));
}

TEST(BubbleForce, RepulsiveBelowOneAttractiveAbove) {
  for (double w = 0.01; w < 1.0; w += 0.01) EXPECT_GT(interBubbleForce(w), 0.0) << w;
  for (double w = 1.01; w < 1.5; w += 0.01) EXPECT_LT(interBubbleForce(w), 0.0) << w;
  // slope −k0 at the rest length: the pair stiffness used to choose Δt
  const double h = 1e-6;
  EXPECT_NEAR((interBubbleForce(1 + h) - interBubbleForce(1 - h)) / (2 * h), -1.0, 1e-6);
}

TEST(BubbleForce, Eq8RadiusIsHalfTheUnitEllipse) {
  const Metric2 m = Metric2::fromSizes(0.4, 0.1, std::numbers::pi / 6);
  const Vec2 e1(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6)), e2(-e1.y(), e1.x());
  EXPECT_NEAR(bubbleRadius(m, 3.0 * e1), 0.2, 1e-12);
  EXPECT_NEAR(bubbleRadius(m, -0.5 * e2), 0.05, 1e-12);
  // two equal bubbles at metric distance 1 touch: l = l0
  const Vec2 d = 0.4 * e1;
  EXPECT_NEAR(restLength(bubbleRadius(m, d), bubbleRadius(m, -d)), d.norm(), 1e-12);
}

TEST(BubbleForce, PairDistanceEq8OrTheAveragedMetricLength) {
  const Metric2 mi = Metric2::fromSizes(0.3, 0.01, 0.2), mj = Metric2::fromSizes(0.1, 0.002, 0.25);
  const Vec2 d(0.05, 0.004);
  const double a2 = mi.squaredLength(d), b2 = mj.squaredLength(d);
  EXPECT_NEAR(pairDistance(a2, b2, PairDistance::Averaged), average(mi, mj).length(d), 1e-12);  // eq. (3)
  EXPECT_NEAR(pairDistance(0.81, 0.81, PairDistance::Averaged), 0.9, 1e-15);  // equal metrics: the length
  EXPECT_NEAR(pairDistance(0.81, 0.81, PairDistance::Harmonic), 0.9, 1e-15);
  EXPECT_NEAR(pairDistance(0.36, 9.0, PairDistance::Harmonic), 1.0, 1e-15);              // a = 0.6, b = 3: at rest
  EXPECT_NEAR(pairDistance(0.36, 9.0, PairDistance::Averaged), std::sqrt(4.68), 1e-15);  // … an edge of length 2.16
  EXPECT_EQ(pairDistance(0.36, 9.0), pairDistance(0.36, 9.0, PairDistance::Harmonic));   // eq. (8) is the default
  EXPECT_EQ(parsePairDistance("averaged"), PairDistance::Averaged);
  EXPECT_STREQ(pairDistanceName(parsePairDistance("eq8")), "eq8");
  EXPECT_THROW(parsePairDistance("mean"), ablmg::InputError);
}

TEST(BubbleForce, MeshOfAJumpyLayerMetricHasShortEdgesAndFewRepairs) {
  // A boundary layer (h2 = 3·10⁻⁴ at y = 0.5, anisotropy up to 300) whose long size h1 swings
  // by 2^±1 every 0.075 along x inside the layer (≈ 1.5 h1: a size ratio near 2 per metric
  // unit, as in the ungraded Hessian metrics of the tanh layer). With eq. (8)'s harmonic w
  // the packing rested where the coarse side wanted it: 95.6 % of edges in [1/√2, √2] and
  // 157 repaired triangles (3.2 %) before PlacementOptions::finalRelaxSteps, 97.4 % with it;
  // with pairDistance 98.8 % and 53 (1.0 %). ~0.15 s.
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  AnalyticMetricField m(AnalyticMetricField::Form::Sizes, "0.05*2^(sin(2*pi*x/0.15)*exp(-((y-0.5)/0.05)^2))",
                        "3e-4+0.1*abs(y-0.5)", "0");
  MeshOptions o;
  o.placement.plateauSteps = 10;
  o.placement.plateauGain = 0.01;
  o.placement.pairDistance = PairDistance::Averaged;
  const MeshResult r = meshDomain(d, m, o);
  ASSERT_TRUE(r.mesh.validate().ok);
  const EdgeLengthStats s = edgeLengthStats(edgeMetricLengths(r.mesh, r.metric));
  EXPECT_GT(s.inSqrt2, 0.98);
  EXPECT_LT(double(r.stats.connect.repairedTriangles), 0.015 * r.mesh.numTriangles());
  o.placement.pairDistance = PairDistance::Harmonic;
  const MeshResult h = meshDomain(d, m, o);
  ASSERT_TRUE(h.mesh.validate().ok);
  EXPECT_LT(edgeLengthStats(edgeMetricLengths(h.mesh, h.metric)).inSqrt2, s.inSqrt2 - 0.005);
}
