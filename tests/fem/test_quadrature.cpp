// Tests of fem/quadrature.hpp: each rule integrates every monomial of its degree exactly.
#include "ablmg/fem/quadrature.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ablmg::fem;

namespace {
double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }
/// ∫_{reference triangle} λ1^a λ2^b dx / |T| = 2 a! b! / (a + b + 2)!
double exactMonomial(int a, int b) { return 2 * factorial(a) * factorial(b) / factorial(a + b + 2); }
}  // namespace

TEST(Quadrature, RulesIntegrateTheirDegreeExactly) {
  for (int request : {1, 2, 3, 4, 5, 6, 7, 8}) {
    const TriangleRule& r = triangleRule(request);
    ASSERT_GE(r.degree, request);
    double wsum = 0;
    for (int q = 0; q < r.size(); ++q) {
      wsum += r.weights[q];
      EXPECT_GT(r.weights[q], 0);
      for (double l : r.points[q]) EXPECT_GT(l, 0);  // strictly interior
      EXPECT_NEAR(r.points[q][0] + r.points[q][1] + r.points[q][2], 1.0, 1e-15);
    }
    EXPECT_NEAR(wsum, 1.0, 1e-13);
    for (int a = 0; a <= r.degree; ++a)
      for (int b = 0; a + b <= r.degree; ++b) {
        double s = 0;
        for (int q = 0; q < r.size(); ++q)
          s += r.weights[q] * std::pow(r.points[q][1], a) * std::pow(r.points[q][2], b);
        EXPECT_NEAR(s, exactMonomial(a, b), 1e-13)
            << "rule of degree " << r.degree << ", monomial x^" << a << " y^" << b;
      }
  }
}

TEST(Quadrature, RulesAreNotExactBeyondTheirDegree) {
  // Guards against a mislabelled rule: some monomial of degree + 1 must fail.
  for (int request : {1, 2, 5, 8}) {
    const TriangleRule& r = triangleRule(request);
    double worst = 0;
    const int d = r.degree + 1;
    for (int a = 0; a <= d; ++a) {
      double s = 0;
      for (int q = 0; q < r.size(); ++q)
        s += r.weights[q] * std::pow(r.points[q][1], a) * std::pow(r.points[q][2], d - a);
      worst = std::max(worst, std::abs(s - exactMonomial(a, d - a)));
    }
    EXPECT_GT(worst, 1e-8) << "degree " << r.degree;
  }
}

TEST(Quadrature, SizesOfTheRules) {
  EXPECT_EQ(triangleRule(1).size(), 1);
  EXPECT_EQ(triangleRule(2).size(), 3);
  EXPECT_EQ(triangleRule(5).size(), 7);
  EXPECT_EQ(triangleRule(6).size(), 16);
  EXPECT_THROW(triangleRule(0), ablmg::InputError);
  EXPECT_THROW(triangleRule(9), ablmg::InputError);
}

TEST(Quadrature, GaussLegendreExactToDegree2nMinus1) {
  for (int n = 1; n <= 3; ++n)
    for (int d = 0; d <= 2 * n - 1; ++d) {
      double s = 0;
      for (const auto& [t, w] : gaussLegendre01(n)) s += w * std::pow(t, d);
      EXPECT_NEAR(s, 1.0 / (d + 1), 1e-15) << n << " points, degree " << d;
    }
}
