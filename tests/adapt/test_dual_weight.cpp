// adapt/dual_weight.hpp: the unit-load dual, the dual-weighted indicators and the density factor.
#include "ablmg/adapt/dual_weight.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
std::vector<double> values(const Mesh2& mesh, const std::function<double(const Vec2&)>& f) {
  std::vector<double> v(mesh.numVertices());
  for (int i = 0; i < mesh.numVertices(); ++i) v[i] = f(mesh.vertices[i]);
  return v;
}
}  // namespace

// −Δz = 1 on the unit square, z = 0 on its boundary: max z = 0.0736713 (the torsion function of
// the square, from its Fourier series), here within the P1 error of a 40×40 grid.
TEST(DualWeight, UnitLoadDualIsTheTorsionFunction) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.0, 0);
  fem::PoissonProblem p;
  p.f = 3.0;
  p.setDirichletEverywhere(fem::ScalarData([](double x, double y) { return x + y; }));
  const fem::PoissonSolution z = fem::solvePoisson(mesh, unitLoadDual(p));
  EXPECT_NEAR(z.u.maxCoeff(), 0.0736713, 1e-3);
  EXPECT_GE(z.u.minCoeff(), -1e-12);
}

TEST(DualWeight, IndicatorsVanishForLinearFieldsAndFollowAFront) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  const auto linear = values(mesh, [](const Vec2& p) { return 2 * p.x() - p.y(); });
  const auto quad = values(mesh, [](const Vec2& p) { return p.x() * (1 - p.x()) * p.y() * (1 - p.y()); });
  for (double e : dualWeightedIndicators(mesh, linear, quad)) EXPECT_NEAR(e, 0, 1e-12);
  for (double s : dualWeightScale(mesh, std::vector<double>(mesh.numTriangles(), 0.0), 0.25)) EXPECT_EQ(s, 1.0);
  // A front at x = 0.5: the factor is larger there than far from it.
  const auto front = values(mesh, [](const Vec2& p) { return std::atan(50 * (p.x() - 0.5)); });
  const auto s = dualWeightScale(mesh, dualWeightedIndicators(mesh, front, quad), 0.25);
  double near = 0, far = 0;
  int nn = 0, nf = 0;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2& p = mesh.vertices[v];
    if (p.y() < 0.2 || p.y() > 0.8) continue;
    if (std::abs(p.x() - 0.5) < 0.03) near += s[v], ++nn;
    if (std::abs(p.x() - 0.5) > 0.3) far += s[v], ++nf;
    EXPECT_GT(s[v], 0);
  }
  ASSERT_GT(nn, 0);
  ASSERT_GT(nf, 0);
  EXPECT_GT(near / nn, 2 * far / nf);
  for (double x : s) {
    EXPECT_LE(x, kMaxFactor);
    EXPECT_GE(x, 1 / kMaxFactor);
  }
  EXPECT_THROW(dualWeightScale(mesh, std::vector<double>(3, 1.0), 0.25), InputError);
  EXPECT_THROW(dualWeightScale(mesh, dualWeightedIndicators(mesh, front, quad), 0), InputError);
}

// The H1 weighting: ε_T is ‖G u − ∇u‖_T itself (the dual's factor with z's part left out), so the
// combined factor with γ = 0 is dualWeightScale of ε, and with both exponents it is the product
// ε^(γ+γ₁) ε_z^γ before the clamp.
TEST(DualWeight, H1WeightingMultipliesTheFactors) {
  const Mesh2 mesh = fem::unitSquareMesh(30, 0.1, 5);
  const auto quad = values(mesh, [](const Vec2& p) { return p.x() * (1 - p.x()) * p.y() * (1 - p.y()); });
  const auto front = values(mesh, [](const Vec2& p) { return std::atan(20 * (p.x() - 0.5)); });
  const auto linear = values(mesh, [](const Vec2& p) { return 2 * p.x() - p.y(); });
  for (double e : recoveryErrorIndicators(mesh, linear)) EXPECT_NEAR(e, 0, 1e-12);
  const auto eu = recoveryErrorIndicators(mesh, front);
  const auto ez = recoveryErrorIndicators(mesh, quad);
  const auto eta = dualWeightedIndicators(mesh, front, quad);
  for (std::size_t t = 0; t < eta.size(); ++t) EXPECT_NEAR(eta[t], eu[t] * ez[t], 1e-12 * (1 + eta[t]));
  EXPECT_EQ(densityWeightScale(mesh, front, {}, 0, 0.25), dualWeightScale(mesh, eu, 0.25));
  EXPECT_EQ(densityWeightScale(mesh, front, quad, 0.25, 0), dualWeightScale(mesh, eta, 0.25));
  std::vector<double> both(eta.size());
  for (std::size_t t = 0; t < eta.size(); ++t) both[t] = std::pow(eu[t], 0.375) * std::pow(ez[t], 0.125);
  const auto s = densityWeightScale(mesh, front, quad, 0.125, 0.25), expect = dualWeightScale(mesh, both, 1.0);
  for (std::size_t v = 0; v < s.size(); ++v) EXPECT_NEAR(s[v], expect[v], 1e-9);
  EXPECT_THROW(densityWeightScale(mesh, front, quad, 0, 0), InputError);
  EXPECT_THROW(densityWeightScale(mesh, front, quad, -0.1, 0.25), InputError);
}
