// Mirrors adapt/convergence.hpp.
#include "ablmg/adapt/convergence.hpp"
#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <vector>

using namespace ablmg::adapt;

TEST(Convergence, SlopeOfPowerLaw) {
  std::vector<double> n{100, 400, 1600, 6400}, e;
  for (double x : n) e.push_back(3 * std::pow(x, -0.5));
  EXPECT_NEAR(logLogSlope(n, e), -0.5, 1e-12);
  e.back() = 1.0;  // only the last k points count
  EXPECT_NEAR(logLogSlope(std::span(n).first(3), std::span(e).first(3), 2), -0.5, 1e-12);
  EXPECT_GT(logLogSlope(n, e, 2), 0);
}

TEST(Convergence, RejectsDegenerateInput) {
  std::vector<double> n{100, 100}, e{1, 2};
  EXPECT_THROW(logLogSlope(n, e), ablmg::InputError);
  std::vector<double> one{1};
  EXPECT_THROW(logLogSlope(one, one), ablmg::InputError);
  std::vector<double> n2{10, 20}, e2{0, 1};
  EXPECT_THROW(logLogSlope(n2, e2), ablmg::InputError);
}

TEST(Convergence, VerticesToReachInterpolatesLogLog) {
  // e = 100 / N on the first segment: e = 2 at N = 50 exactly.
  std::vector<double> n{10, 100, 1000}, e{10, 1, 0.5};
  EXPECT_NEAR(verticesToReach(n, e, 2.0), 50.0, 1e-9);
  EXPECT_NEAR(verticesToReach(n, e, 1.0), 100.0, 1e-9);
  EXPECT_NEAR(verticesToReach(n, e, 20.0), 10.0, 0);    // already reached at the first point
  EXPECT_TRUE(std::isnan(verticesToReach(n, e, 0.1)));  // never reached
  // A curve that rises again: the first crossing counts.
  std::vector<double> n2{10, 100, 1000, 10000}, e2{10, 1, 5, 0.1};
  EXPECT_NEAR(verticesToReach(n2, e2, 1.0), 100.0, 1e-9);
  std::vector<double> bad{1, -1};
  EXPECT_THROW(verticesToReach(n, bad, 1.0), ablmg::InputError);
  EXPECT_THROW(verticesToReach(n, e, 0.0), ablmg::InputError);
}
