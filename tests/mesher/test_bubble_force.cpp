#include "mesher/bubble_force.hpp"

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
