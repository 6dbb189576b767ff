// Mirrors fem/material_problems.hpp, with PoissonProblem::kappaBySubdomain (fem/assemble.hpp)
// and gridRegionMesh (fem/structured_mesh.hpp): a two-material problem whose exact solution is
// piecewise linear is reproduced to round-off (one κ could not: the kink sits on the
// interface), a ref without data is refused, the battery's regions are a valid mesh of its
// rectangle with five materials and their interfaces.
#include "ablmg/fem/material_problems.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace ablmg;
using namespace ablmg::fem;

namespace {
/// −(κ u')' = 0 on (0,1), κ = k1 for x < 0.5, k2 beyond, u(0) = 0, u(1) = 1: the flux
/// κ u' is the same on both sides, so u is linear on each with slopes in the ratio k2 : k1.
double twoMaterialU(double x, double k1, double k2) {
  const double s1 = 2 * k2 / (k1 + k2), s2 = 2 * k1 / (k1 + k2);  // s1/2 + s2/2 = 1, k1 s1 = k2 s2
  return x < 0.5 ? s1 * x : 0.5 * s1 + s2 * (x - 0.5);
}

Mesh2 twoMaterialSquare(int n) {
  std::vector<double> xs, ys;
  for (int i = 0; i <= n; ++i) xs.push_back(double(i) / n);
  for (int j = 0; j <= 3; ++j) ys.push_back(j / 3.0);
  return gridRegionMesh(xs, ys, [](double x, double) { return x < 0.5 ? 1 : 2; });
}
}  // namespace

TEST(MaterialProblems, PiecewiseKappaReproducesThePiecewiseLinearSolution) {
  const Mesh2 m = twoMaterialSquare(8);
  ASSERT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
  EXPECT_EQ(m.interfaceEdges.size(), 3u);  // x = 0.5, three cells high
  for (const auto& e : m.interfaceEdges) EXPECT_EQ(e.ref, 12);
  PoissonProblem p;
  p.kappaBySubdomain = {{1, 1.0}, {2, 40.0}};
  p.dirichlet = {{2, 1.0}, {4, 0.0}};  // right u = 1, left u = 0; bottom and top insulated
  const auto sol = solvePoisson(m, p);
  double err = 0;
  for (int v = 0; v < m.numVertices(); ++v)
    err = std::max(err, std::abs(sol.u[v] - twoMaterialU(m.vertices[std::size_t(v)].x(), 1, 40)));
  EXPECT_LT(err, 1e-12);
  // with one κ everywhere the same mesh gives u = x, far from the two-material solution
  PoissonProblem one = p;
  one.kappaBySubdomain.clear();
  const auto u1 = solvePoisson(m, one).u;
  double gap = 0;
  for (int v = 0; v < m.numVertices(); ++v)
    gap = std::max(gap, std::abs(u1[v] - twoMaterialU(m.vertices[std::size_t(v)].x(), 1, 40)));
  EXPECT_GT(gap, 0.4);
}

TEST(MaterialProblems, PerSubdomainLoadIsIntegratedOnItsSubdomainOnly) {
  const Mesh2 m = twoMaterialSquare(8);
  PoissonProblem p;
  p.fBySubdomain = {{1, 0.0}, {2, 3.0}};
  p.dirichlet[1] = 0.0;  // bottom only: most vertices are unknowns
  const auto sys = assemble(m, p);
  double total = 0;
  for (int d = 0; d < int(sys.b.size()); ++d) {
    const Vec2 x = sys.dofPoints[std::size_t(d)];
    if (x.x() < 0.5) { EXPECT_EQ(sys.b[d], 0.0) << "load in material 1 at " << x.transpose(); }
    total += sys.b[d];
  }
  // ∫ f = 3 · 1/2, less the part on the bottom row's vertices (a third of the height at most)
  EXPECT_GT(total, 1.5 * (1 - 1.0 / 3) - 1e-12);
  EXPECT_LE(total, 1.5 + 1e-12);
}

TEST(MaterialProblems, ARefWithoutDataIsAnErrorNamingIt) {
  const Mesh2 m = twoMaterialSquare(4);
  PoissonProblem p;
  p.kappaBySubdomain = {{1, 1.0}};
  p.setDirichletEverywhere(0.0);
  try {
    (void)assemble(m, p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("subdomain ref 2"), std::string::npos) << e.what();
  }
  p.kappaBySubdomain = {{1, 1.0}, {2, -1.0}};
  EXPECT_THROW((void)assemble(m, p), InputError);
}

TEST(MaterialProblems, BatteryRegionsAreAValidMeshOfFiveMaterials) {
  const MaterialProblem b = makeMaterialProblem("battery");
  ASSERT_TRUE(b.regions.validate(8.4 * 24, 1e-12).ok) << b.regions.validate().firstProblem;
  std::map<int, double> area;
  for (int t = 0; t < b.regions.numTriangles(); ++t)
    area[b.regions.triangleRefs[std::size_t(t)]] += b.regions.triangleArea(t);
  ASSERT_EQ(area.size(), 5u);
  EXPECT_NEAR(area[3], 5.3 * 8.4, 1e-10);
  EXPECT_NEAR(area[2], 5.3 * (2.0 + 6.8), 1e-10);
  EXPECT_NEAR(area[4], 0.8 * 19.6, 1e-10);
  EXPECT_NEAR(area[5], 6.9 * 2.8, 1e-10);
  for (int m = 1; m <= 5; ++m) {
    EXPECT_TRUE(b.pde.kappaBySubdomain.count(m));
    EXPECT_TRUE(b.pde.fBySubdomain.count(m));
  }
  std::set<int> refs;
  for (const auto& e : b.regions.interfaceEdges) refs.insert(e.ref);
  EXPECT_GE(refs.size(), 5u);
  EXPECT_THROW((void)makeMaterialProblem("batery"), InputError);
  EXPECT_THROW((void)makeMaterialProblem("battery", {{"alpha", 1}}), InputError);
  EXPECT_THROW((void)gridRegionMesh({0, 0}, {0, 1}, [](double, double) { return 1; }), InputError);
}
