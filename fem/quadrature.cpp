#include "ablmg/fem/quadrature.hpp"

#include "ablmg/core/error.hpp"

#include <cmath>

namespace ablmg::fem {
namespace {

// Symmetry orbits of a symmetric rule: S3 (centroid), S21 (a, b, b) × 3, S111 (a, b, c) × 6.
void addS3(TriangleRule& r, double w) {
  r.points.push_back({1.0 / 3, 1.0 / 3, 1.0 / 3});
  r.weights.push_back(w);
}
void addS21(TriangleRule& r, double a, double w) {
  const double b = 0.5 * (1 - a);
  for (const auto& p : {std::array<double, 3>{a, b, b}, {b, a, b}, {b, b, a}}) {
    r.points.push_back(p);
    r.weights.push_back(w);
  }
}
void addS111(TriangleRule& r, double a, double b, double w) {
  const double c = 1 - a - b;
  for (const auto& p : {std::array<double, 3>{a, b, c}, {a, c, b}, {b, a, c}, {b, c, a}, {c, a, b}, {c, b, a}}) {
    r.points.push_back(p);
    r.weights.push_back(w);
  }
}

TriangleRule makeDegree1() {
  TriangleRule r;
  r.degree = 1;
  addS3(r, 1.0);
  return r;
}

TriangleRule makeDegree2() {
  TriangleRule r;
  r.degree = 2;
  addS21(r, 2.0 / 3.0, 1.0 / 3.0);
  return r;
}

TriangleRule makeDegree5() {  // Radon's 7-point rule
  TriangleRule r;
  r.degree = 5;
  const double s = std::sqrt(15.0);
  addS3(r, 9.0 / 40.0);
  addS21(r, 1 - 2 * (6 - s) / 21, (155 - s) / 1200);  // b = (6 − √15)/21
  addS21(r, 1 - 2 * (6 + s) / 21, (155 + s) / 1200);  // b = (6 + √15)/21
  return r;
}

TriangleRule makeDegree8() {  // Dunavant (1985), degree 8, 16 points
  TriangleRule r;
  r.degree = 8;
  addS3(r, 0.144315607677787);
  addS21(r, 0.081414823414554, 0.095091634267285);
  addS21(r, 0.658861384496480, 0.103217370534718);
  addS21(r, 0.898905543365938, 0.032458497623198);
  addS111(r, 0.008394777409958, 0.263112829634638, 0.027230314174435);
  return r;
}

}  // namespace

const TriangleRule& triangleRule(int degree) {
  static const TriangleRule r1 = makeDegree1(), r2 = makeDegree2(), r5 = makeDegree5(), r8 = makeDegree8();
  ABLMG_REQUIRE(degree >= 1 && degree <= 8, "triangleRule: degree " << degree << " is outside [1, 8]");
  if (degree <= 1) return r1;
  if (degree <= 2) return r2;
  if (degree <= 5) return r5;
  return r8;
}

const std::vector<std::array<double, 2>>& gaussLegendre01(int n) {
  static const std::vector<std::array<double, 2>> g1{{0.5, 1.0}};
  static const std::vector<std::array<double, 2>> g2{{0.5 - 0.5 / std::sqrt(3.0), 0.5},
                                                     {0.5 + 0.5 / std::sqrt(3.0), 0.5}};
  static const std::vector<std::array<double, 2>> g3{
      {0.5 - 0.5 * std::sqrt(0.6), 5.0 / 18}, {0.5, 8.0 / 18}, {0.5 + 0.5 * std::sqrt(0.6), 5.0 / 18}};
  ABLMG_REQUIRE(n >= 1 && n <= 3, "gaussLegendre01: " << n << " points requested, 1 to 3 available");
  return n == 1 ? g1 : n == 2 ? g2 : g3;
}

}  // namespace ablmg::fem
