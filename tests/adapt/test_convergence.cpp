// Mirrors adapt/convergence.hpp.
#include "adapt/convergence.hpp"
#include "core/error.hpp"

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
