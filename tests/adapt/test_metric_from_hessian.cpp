// Mirrors adapt/metric_from_hessian.hpp: the requested complexity, the bounds, the Lp scaling.
#include "adapt/metric_from_hessian.hpp"
#include "core/error.hpp"
#include "fem/structured_mesh.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>
#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
// Hessians of the wave-front-like u = atan(20 (r − 0.7)): strongly anisotropic near the front.
std::vector<Hessian2> frontHessians(const Mesh2& mesh) {
  std::vector<Hessian2> h(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 d = mesh.vertices[v] + Vec2(0.05, 0.05);
    const double r = d.norm(), a = 20, s = a * (r - 0.7);
    const double up = a / (1 + s * s), upp = -2 * a * a * s / ((1 + s * s) * (1 + s * s));
    const Vec2 n = d / r;
    h[v] = upp * n * n.transpose() + up / r * (Eigen::Matrix2d::Identity() - n * n.transpose());
  }
  return h;
}
} // namespace

TEST(MetricFromHessian, ComplexityMatchesTarget) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  const auto h = frontHessians(mesh);
  for (double p : {1.0, 2.0, std::numeric_limits<double>::infinity()}) {
    for (double n : {1000.0, 20000.0}) {
      MetricOptions o;
      o.targetVertices = n;
      o.p = p;
      const auto m = metricFromHessians(mesh, h, o);
      EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(n), 1.0, 2e-3) << "p " << p << " N " << n;
    }
  }
}

TEST(MetricFromHessian, ComplexityMatchesTargetWithActiveBounds) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  MetricOptions o;
  o.targetVertices = 5000;
  o.hmin = 0.004;
  o.hmax = 0.03;
  o.maxAnisotropy = 2;
  const auto m = metricFromHessians(mesh, frontHessians(mesh), o);
  EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(5000), 1.0, 2e-3);
  int hitMax = 0, hitAniso = 0;
  for (const auto& x : m) {
    const auto e = x.eigen();
    EXPECT_GE(e.h2, o.hmin * (1 - 1e-9));
    EXPECT_LE(e.h1, o.hmax * (1 + 1e-9));
    EXPECT_LE(e.h1 / e.h2, o.maxAnisotropy * (1 + 1e-9));
    hitMax += e.h1 > 0.999 * o.hmax;
    hitAniso += e.h1 / e.h2 > 0.999 * o.maxAnisotropy;
  }
  EXPECT_GT(hitMax, 0);    // the bounds were active, so the test means something
  EXPECT_GT(hitAniso, 0);
}

TEST(MetricFromHessian, LpScalingOfAConstantHessian) {
  // Constant H = diag(a, b): M = D |H| for every p (the det factor is constant), and
  // D · sqrt(ab) · area = (√3/2) N. Eigenvectors and the anisotropy sqrt(a/b) are kept.
  const Mesh2 mesh = fem::unitSquareMesh(6, 0.2, 1);
  std::vector<Hessian2> h(mesh.numVertices());
  for (auto& x : h) x << -100, 0, 0, 4;  // absolute value: diag(100, 4)
  MetricOptions o;
  o.targetVertices = 1000;
  const auto m = metricFromHessians(mesh, h, o);
  const double d = complexityForVertices(1000) / std::sqrt(400.0);
  for (const auto& x : m) {
    EXPECT_NEAR(x.m11(), 100 * d, 1e-9 * 100 * d);
    EXPECT_NEAR(x.m22(), 4 * d, 1e-9 * 100 * d);
    EXPECT_NEAR(x.m12(), 0, 1e-9 * d);
  }
}

TEST(MetricFromHessian, ZeroHessianGivesUniformMetric) {
  const Mesh2 mesh = fem::unitSquareMesh(5);
  std::vector<Hessian2> h(mesh.numVertices(), Hessian2::Zero());
  MetricOptions o;
  o.targetVertices = 400;
  const auto m = metricFromHessians(mesh, h, o);
  const double hExpected = std::sqrt(1.0 / complexityForVertices(400));
  for (const auto& x : m) {
    EXPECT_NEAR(x.eigen().h1, hExpected, 1e-9);
    EXPECT_NEAR(x.eigen().h2, hExpected, 1e-9);
  }
}

TEST(MetricFromHessian, AbsoluteHessianAndIntersection) {
  Hessian2 h;
  h << 1, 2, 2, 1;  // eigenvalues 3, −1
  const Hessian2 a = absoluteHessian(h, 1e-12);
  EXPECT_NEAR(a(0, 0), 2, 1e-12);
  EXPECT_NEAR(a(0, 1), 1, 1e-12);
  EXPECT_NEAR(a.determinant(), 3, 1e-12);
  const std::vector<Metric2> x{Metric2::fromSizes(1, 0.1, 0)}, y{Metric2::fromSizes(1, 0.1, M_PI / 2)};
  const auto z = intersectFields(x, y);
  EXPECT_NEAR(z[0].eigen().h1, 0.1, 1e-9);
  EXPECT_NEAR(z[0].eigen().h2, 0.1, 1e-9);
}

TEST(MetricFromHessian, RejectsBadOptions) {
  const Mesh2 mesh = fem::unitSquareMesh(3);
  std::vector<Hessian2> h(mesh.numVertices(), Hessian2::Identity());
  MetricOptions o;
  o.p = 0.5;
  EXPECT_THROW(metricFromHessians(mesh, h, o), InputError);
  o = {};
  o.hmin = 1;
  o.hmax = 0.5;
  EXPECT_THROW(metricFromHessians(mesh, h, o), InputError);
  o = {};
  o.targetVertices = -3;
  EXPECT_THROW(metricFromHessians(mesh, h, o), InputError);
  h.pop_back();
  EXPECT_THROW(metricFromHessians(mesh, h, MetricOptions{}), InputError);
}
