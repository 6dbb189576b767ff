// Mirrors adapt/hessian_recovery.hpp: both methods reproduce the Hessian of a quadratic at
// every vertex (boundary included) on perturbed ("unstructured") meshes; second order on a
// smooth function; bad input rejected.
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>
#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
double quadratic(const Vec2& p) {
  const double x = p.x(), y = p.y();
  return 1 + 2 * x - 3 * y + 4 * x * x - 5 * x * y + 6 * y * y;
}
std::vector<double> sample(const Mesh2& m, double (*f)(const Vec2&)) {
  std::vector<double> u(m.numVertices());
  for (int v = 0; v < m.numVertices(); ++v) u[v] = f(m.vertices[v]);
  return u;
}
void expectExactForQuadratic(const Mesh2& mesh, HessianMethod method) {
  const auto u = sample(mesh, quadratic);
  const auto h = recoverHessians(mesh, u, method);
  ASSERT_EQ(int(h.size()), mesh.numVertices());
  Hessian2 exact;
  exact << 8, -5, -5, 12;
  double worst = 0;
  for (int v = 0; v < mesh.numVertices(); ++v) worst = std::max(worst, (h[v] - exact).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 1e-8) << toString(method);
}
}  // namespace

TEST(HessianRecovery, ExactForQuadraticsOnPerturbedSquare) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const Mesh2 mesh = fem::unitSquareMesh(13, 0.2, seed);
    expectExactForQuadratic(mesh, HessianMethod::LeastSquares);
    expectExactForQuadratic(mesh, HessianMethod::DoubleRecovery);
  }
}

TEST(HessianRecovery, ExactForQuadraticsOnPerturbedLShapeIncludingReentrantCorner) {
  const Mesh2 mesh = fem::structuredMesh(fem::makeProblem("lshape").domain, 10, 10, 0.2, 7);
  expectExactForQuadratic(mesh, HessianMethod::LeastSquares);
  expectExactForQuadratic(mesh, HessianMethod::DoubleRecovery);
}

TEST(HessianRecovery, ExactForQuadraticsOnCoarsestMeshes) {
  // 2×2 cells: 9 vertices; every patch has to grow to the whole mesh.
  expectExactForQuadratic(fem::unitSquareMesh(2, 0.0), HessianMethod::LeastSquares);
  expectExactForQuadratic(fem::unitSquareMesh(3, 0.1, 5), HessianMethod::DoubleRecovery);
}

TEST(HessianRecovery, GradientsExactForQuadratics) {
  const Mesh2 mesh = fem::unitSquareMesh(9, 0.2, 4);
  const auto g = recoverGradients(mesh, sample(mesh, quadratic));
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const double x = mesh.vertices[v].x(), y = mesh.vertices[v].y();
    EXPECT_NEAR(g[v].x(), 2 + 8 * x - 5 * y, 1e-9);
    EXPECT_NEAR(g[v].y(), -3 - 5 * x + 12 * y, 1e-9);
  }
}

TEST(HessianRecovery, AreaWeightedGradientExactForLinear) {
  const Mesh2 mesh = fem::unitSquareMesh(7, 0.2, 9);
  std::vector<double> u(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) u[v] = 3 * mesh.vertices[v].x() - 7 * mesh.vertices[v].y();
  for (const auto& g : areaWeightedGradients(mesh, u)) {
    EXPECT_NEAR(g.x(), 3, 1e-12);
    EXPECT_NEAR(g.y(), -7, 1e-12);
  }
}

TEST(HessianRecovery, ConvergesOnSmoothFunction) {
  // sin(πx) sin(πy): the RMS Hessian error falls (about first order) under refinement.
  auto errorAt = [](int n, HessianMethod method) {
    const Mesh2 mesh = fem::unitSquareMesh(n, 0.15, 11);
    std::vector<double> u(mesh.numVertices());
    for (int v = 0; v < mesh.numVertices(); ++v)
      u[v] = std::sin(M_PI * mesh.vertices[v].x()) * std::sin(M_PI * mesh.vertices[v].y());
    const auto h = recoverHessians(mesh, u, method);
    double sum = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double x = mesh.vertices[v].x(), y = mesh.vertices[v].y(), s = M_PI * M_PI;
      Hessian2 e;
      e << -s * std::sin(M_PI * x) * std::sin(M_PI * y), s * std::cos(M_PI * x) * std::cos(M_PI * y),
          s * std::cos(M_PI * x) * std::cos(M_PI * y), -s * std::sin(M_PI * x) * std::sin(M_PI * y);
      sum += (h[v] - e).squaredNorm();
    }
    return std::sqrt(sum / mesh.numVertices());  // root mean square over the vertices
  };
  for (auto method : {HessianMethod::LeastSquares, HessianMethod::DoubleRecovery}) {
    const double e1 = errorAt(16, method), e2 = errorAt(32, method);
    EXPECT_LT(e2, 0.6 * e1) << toString(method) << " " << e1 << " -> " << e2;
    EXPECT_LT(e2, 0.5) << toString(method);
  }
}

TEST(HessianRecovery, RejectsBadInput) {
  const Mesh2 mesh = fem::unitSquareMesh(3);
  std::vector<double> u(mesh.numVertices() - 1, 0.0);
  EXPECT_THROW(recoverHessians(mesh, u, HessianMethod::LeastSquares), InputError);
  u.assign(mesh.numVertices(), 0.0);
  u[4] = std::nan("");
  EXPECT_THROW(recoverHessians(mesh, u, HessianMethod::DoubleRecovery), InputError);
  EXPECT_THROW(parseHessianMethod("cubic"), InputError);
  EXPECT_EQ(parseHessianMethod("double"), HessianMethod::DoubleRecovery);
}

namespace {
/// A kink across x = 0.5 (the gradient jumps by 3, as a P1 solution's does across an interface
/// between materials): quadratic (u_xx = 2) on each side, refs 1 (x < 0.5) and 2.
double kinked(const Vec2& p) { return p.x() * p.x() + 3 * std::max(p.x() - 0.5, 0.0) + 0.5 * p.y(); }
Mesh2 twoMaterialGrid(int n) {
  std::vector<double> xs, ys;
  for (int i = 0; i <= n; ++i) xs.push_back(double(i) / n), ys.push_back(double(i) / n);
  return fem::gridRegionMesh(xs, ys, [](double x, double) { return x < 0.5 ? 1 : 2; });
}
}  // namespace

TEST(HessianRecovery, SubdomainsAreRecoveredApartSoAKinkOnTheInterfaceIsNoCurvature) {
  Mesh2 mesh = twoMaterialGrid(16);
  const auto u = sample(mesh, kinked);
  for (HessianMethod method : {HessianMethod::LeastSquares, HessianMethod::DoubleRecovery}) {
    const auto h = recoverHessians(mesh, u, method);
    double worst = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) worst = std::max(worst, std::abs(h[std::size_t(v)](0, 0) - 2));
    // exact: each side is a quadratic, recovered on its own
    EXPECT_LT(worst, 1e-6) << toString(method);
    // one subdomain: the fit across the kink reads it as a curvature of order 3/h there
    Mesh2 one = mesh;
    one.triangleRefs.assign(one.triangles.size(), 1);
    one.interfaceEdges.clear();
    const auto h1 = recoverHessians(one, u, method);
    double across = 0;
    for (int v = 0; v < one.numVertices(); ++v) across = std::max(across, std::abs(h1[std::size_t(v)](0, 0)));
    EXPECT_GT(across, 10.0) << toString(method);
  }
}

TEST(HessianRecovery, CombinedInterfaceHessianIsTheIntersectionOfTheAbsoluteValues) {
  Hessian2 a, b;
  a << 4, 0, 0, -1;  // |a| = diag(4, 1)
  b << 1, 0, 0, 9;
  const Hessian2 c = detail::combineSubdomainHessians(a, b);
  EXPECT_NEAR(c(0, 0), 4, 1e-12);
  EXPECT_NEAR(c(1, 1), 9, 1e-12);
  EXPECT_NEAR(c(0, 1), 0, 1e-12);
  const Hessian2 z = Hessian2::Zero();
  EXPECT_NEAR((detail::combineSubdomainHessians(z, a) - Hessian2(Eigen::Vector2d(4, 1).asDiagonal())).norm(), 0, 1e-12);
  // along every direction the combined form is at least each one's
  Hessian2 r;
  r << 2, 1.5, 1.5, 3;
  const Hessian2 cr = detail::combineSubdomainHessians(a, r);
  for (int k = 0; k < 16; ++k) {
    const Eigen::Vector2d d(std::cos(k * 0.2), std::sin(k * 0.2));
    EXPECT_GE(d.dot(cr * d), d.dot(Eigen::Vector2d(4 * d.x(), d.y())) - 1e-10);
    EXPECT_GE(d.dot(cr * d), d.dot(r * d) - 1e-10);
  }
}

TEST(HessianRecovery, TwoFieldsAtOnceAreEachFieldsOwn) {
  // A solution and its dual on one mesh share the patches: the two-field recovery gives each
  // field's Hessians bit for bit, on a graded mesh with a reentrant corner.
  const Mesh2 mesh = fem::structuredMesh(fem::makeProblem("lshape").domain, 12, 12, 0.2, 5);
  std::vector<double> u(std::size_t(mesh.numVertices())), z(u.size());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 p = mesh.vertices[std::size_t(v)];
    u[std::size_t(v)] = std::sin(3 * p.x()) * std::exp(p.y());
    z[std::size_t(v)] = (1 - p.x() * p.x()) * (1 - p.y() * p.y()) + 0.1 * std::cos(5 * p.x() * p.y());
  }
  const auto both = recoverHessians(mesh, u, z, HessianMethod::LeastSquares);
  const auto hu = recoverHessians(mesh, u, HessianMethod::LeastSquares);
  const auto hz = recoverHessians(mesh, z, HessianMethod::LeastSquares);
  ASSERT_EQ(both[0].size(), hu.size());
  ASSERT_EQ(both[1].size(), hz.size());
  for (std::size_t v = 0; v < hu.size(); ++v) {
    EXPECT_EQ(both[0][v], hu[v]) << v;
    EXPECT_EQ(both[1][v], hz[v]) << v;
  }
}
