// Mirrors adapt/metric_from_hessian.hpp: the requested complexity, the bounds, the Lp scaling,
// and the H1 (W^{1,p} seminorm) metric: shape |H|²/det|H|, density det|H|^(p/(p+2)).
#include "ablmg/adapt/metric_from_hessian.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <optional>

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
}  // namespace

TEST(MetricFromHessian, ComplexityMatchesTarget) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  const auto h = frontHessians(mesh);
  for (ErrorNorm norm : {ErrorNorm::L2, ErrorNorm::H1}) {
    for (double p : {1.0, 2.0, std::numeric_limits<double>::infinity()}) {
      for (double n : {1000.0, 20000.0}) {
        MetricOptions o;
        o.targetVertices = n;
        o.p = p;
        o.norm = norm;
        const auto m = metricFromHessians(mesh, h, o);
        EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(n), 1.0, 2e-3)
            << toString(norm) << " p " << p << " N " << n;
      }
    }
  }
}

TEST(MetricFromHessian, ComplexityMatchesTargetWithActiveBounds) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  for (ErrorNorm norm : {ErrorNorm::L2, ErrorNorm::H1}) {
    SCOPED_TRACE(toString(norm));
    MetricOptions o;
    o.norm = norm;
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
    EXPECT_GT(hitMax, 0);  // the bounds were active, so the test means something
    EXPECT_GT(hitAniso, 0);
  }
}

// hmaxUniform κ: h ≤ κ h_N, h_N = √(2|Ω|/(√3 N)) (|Ω| = 1 here), at the requested complexity.
TEST(MetricFromHessian, HmaxUniformBoundsTheLargestSize) {
  const Mesh2 mesh = fem::unitSquareMesh(40, 0.1, 3);
  MetricOptions o;
  o.targetVertices = 5000;
  o.p = std::numeric_limits<double>::infinity();
  const double hN = std::sqrt(2 / (std::sqrt(3.0) * 5000));
  double largest = 0;
  for (const auto& x : metricFromHessians(mesh, frontHessians(mesh), o)) largest = std::max(largest, x.eigen().h1);
  ASSERT_GT(largest, 3 * hN);  // without the floor the far field is coarser: the bound below is active
  o.hmaxUniform = 2;
  EXPECT_NEAR(effectiveHmax(mesh, o), 2 * hN, 1e-12);
  const auto m = metricFromHessians(mesh, frontHessians(mesh), o);
  EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(5000), 1.0, 2e-3);
  int hit = 0;
  for (const auto& x : m) {
    EXPECT_LE(x.eigen().h1, 2 * hN * (1 + 1e-9));
    hit += x.eigen().h1 > 0.999 * 2 * hN;
  }
  EXPECT_GT(hit, 0);
  o.hmaxUniform = 0;
  EXPECT_THROW(validate(o), InputError);
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

namespace {
Hessian2 rotated(double a, double b, double theta) {  // R diag(a, b) Rᵀ, R the rotation by theta
  Eigen::Matrix2d r;
  r << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return r * Eigen::Vector2d(a, b).asDiagonal() * r.transpose();
}
}  // namespace

TEST(MetricFromHessian, H1MetricOfAConstantHessian) {
  // Constant H = R diag(−100, 4) Rᵀ: M_{1,2} = D |H|²/√det|H| with D = C / ∫ √det|H| = C/20, so
  // M = C R diag(10⁴/400, 16/400) Rᵀ = C R diag(25, 0.04) Rᵀ: eigenvalue ratio (λ1/λ2)² = 625
  // (the Lp metric's is λ1/λ2 = 25), eigenvectors those of H, complexity C on the unit square.
  const Mesh2 mesh = fem::unitSquareMesh(6, 0.2, 1);
  const double theta = 0.3;
  std::vector<Hessian2> h(mesh.numVertices(), rotated(-100, 4, theta));
  MetricOptions o;
  o.targetVertices = 1000;
  o.norm = ErrorNorm::H1;
  const double c = complexityForVertices(1000);
  const Hessian2 expected = rotated(25 * c, 0.04 * c, theta);
  for (const auto& x : metricFromHessians(mesh, h, o)) {
    EXPECT_NEAR(x.m11(), expected(0, 0), 1e-9 * 25 * c);
    EXPECT_NEAR(x.m12(), expected(0, 1), 1e-9 * 25 * c);
    EXPECT_NEAR(x.m22(), expected(1, 1), 1e-9 * 25 * c);
    const auto e = x.eigen();
    EXPECT_NEAR(e.h1 / e.h2, 25.0, 1e-9);  // size ratio λ1/λ2 (Lp: √(λ1/λ2) = 5)
  }
  // Lp for comparison: eigenvalue ratio λ1/λ2 = 25, i.e. size ratio 5.
  o.norm = ErrorNorm::L2;
  for (const auto& x : metricFromHessians(mesh, h, o)) EXPECT_NEAR(x.eigen().h1 / x.eigen().h2, 5.0, 1e-9);
}

TEST(MetricFromHessian, DensityAndShapeExponentsBetweenTwoRegions) {
  // Two Hessians on the two halves of the square, det|H| 4 (left) and 256 (right), anisotropy
  // 4 and 4 with different axes. Vertex by vertex (the global D cancels in ratios):
  //   √det M_right / √det M_left = (256/4)^δ,  δ = p/(p+2) (H1), p/(2p+2) (L2),
  //   eigenvalue ratio of M = (λ1/λ2)^(1+w),  w = 1 (H1), 0 (L2), or shapeBlend.
  const Mesh2 mesh = fem::unitSquareMesh(8, 0.0, 1);
  std::vector<Hessian2> h(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v)
    h[v] = mesh.vertices[v].x() < 0.5 ? rotated(1, 4, 0) : rotated(32, -8, 1.0);  // det 4, det 256
  struct Case {
    ErrorNorm norm;
    double p;
    std::optional<double> blend;
    double delta, s;
  };
  const double inf = std::numeric_limits<double>::infinity();
  for (const Case& k : {Case{ErrorNorm::H1, 2, {}, 0.5, 2}, Case{ErrorNorm::H1, 4, {}, 4.0 / 6, 2},
                        Case{ErrorNorm::H1, inf, {}, 1.0, 2}, Case{ErrorNorm::L2, 2, {}, 1.0 / 3, 1},
                        Case{ErrorNorm::L2, 4, {}, 0.4, 1}, Case{ErrorNorm::L2, 4, 0.5, 0.4, 1.5},
                        Case{ErrorNorm::H1, 2, 0.0, 0.5, 1}}) {
    MetricOptions o;
    o.targetVertices = 3000;
    o.norm = k.norm;
    o.p = k.p;
    o.shapeBlend = k.blend;
    SCOPED_TRACE(toString(k.norm) + " p " + std::to_string(k.p) + " blend " + std::to_string(k.blend.value_or(-1)));
    const auto m = metricFromHessians(mesh, h, o);
    double left = 0, right = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double x = mesh.vertices[v].x(), sq = std::sqrt(m[v].det());
      const auto e = m[v].eigen();
      EXPECT_NEAR(std::log(e.h1 / e.h2), 0.5 * k.s * std::log(4.0), 1e-9);  // size ratio (λ1/λ2)^(s/2)
      (x < 0.5 ? left : right) = sq;
    }
    EXPECT_NEAR(std::log(right / left), k.delta * std::log(64.0), 1e-9);
  }
}

TEST(MetricFromHessian, ZeroShapeBlendIsTheLpMetric) {
  // The general formula det|H|^δ (|H|/√det|H|)^(1+w) at w = 0 is the Lp metric, to round-off.
  const Mesh2 mesh = fem::unitSquareMesh(30, 0.1, 5);
  const auto h = frontHessians(mesh);
  MetricOptions o;
  o.targetVertices = 4000;
  o.p = 4;
  const auto a = metricFromHessians(mesh, h, o);
  o.shapeBlend = 0.0;
  const auto b = metricFromHessians(mesh, h, o);
  for (std::size_t v = 0; v < a.size(); ++v) {
    const double scale = std::max({std::abs(a[v].m11()), std::abs(a[v].m22()), 1.0});
    EXPECT_NEAR(a[v].m11(), b[v].m11(), 1e-9 * scale);
    EXPECT_NEAR(a[v].m12(), b[v].m12(), 1e-9 * scale);
    EXPECT_NEAR(a[v].m22(), b[v].m22(), 1e-9 * scale);
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
  o = {};
  o.shapeBlend = 1.5;
  EXPECT_THROW(metricFromHessians(mesh, h, o), InputError);
  o.shapeBlend = -0.1;
  EXPECT_THROW(metricFromHessians(mesh, h, o), InputError);
  EXPECT_THROW(parseErrorNorm("h2"), InputError);
  EXPECT_EQ(parseErrorNorm("h1"), ErrorNorm::H1);
  EXPECT_EQ(toString(parseErrorNorm("l2")), "l2");
  h.pop_back();
  EXPECT_THROW(metricFromHessians(mesh, h, MetricOptions{}), InputError);
}

TEST(MetricFromHessian, SaddleShapeMakesTheAlignedRightIsoscelesTriangleEquilateral) {
  // H = R diag(1, −1) Rᵀ (a harmonic saddle turned by 0.3): at σ = 1 the legs R e_x, R e_y and
  // the diagonal R (e_x + e_y) have one length in the shaped metric, det is kept, and a definite
  // Hessian or σ = 0 leaves the shape alone.
  const double t = 0.3, c = std::cos(t), s = std::sin(t);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  const Hessian2 h = r * Eigen::Vector2d(1, -1).asDiagonal() * r.transpose();
  const Hessian2 shape = 4 * Hessian2::Identity();
  const Hessian2 m = saddleShaped(h, shape, 1);
  const Eigen::Vector2d ex = r.col(0), ey = r.col(1);
  const double lx = ex.dot(m * ex), ly = ey.dot(m * ey), ld = (ex + ey).dot(m * (ex + ey));
  EXPECT_NEAR(ly / lx, 1, 1e-12);
  EXPECT_NEAR(ld / lx, 1, 1e-12);
  EXPECT_NEAR(m.determinant(), shape.determinant(), 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m);
  EXPECT_NEAR(es.eigenvalues()[1] / es.eigenvalues()[0], 3, 1e-12);  // aspect √3
  EXPECT_NEAR((saddleShaped(h, shape, 0) - shape).norm(), 0, 1e-12);
  const Hessian2 definite = r * Eigen::Vector2d(2, 1).asDiagonal() * r.transpose();
  EXPECT_NEAR((saddleShaped(definite, shape, 1) - shape).norm(), 0, 1e-12);
  // Half the weight at r = −0.6 (σ = 1): aspect 3^(1/4); none at r = −0.5.
  const Hessian2 weak = r * Eigen::Vector2d(1, -0.6).asDiagonal() * r.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> ew(saddleShaped(weak, shape, 1));
  EXPECT_NEAR(ew.eigenvalues()[1] / ew.eigenvalues()[0], std::sqrt(3.0), 1e-9);
  const Hessian2 weaker = r * Eigen::Vector2d(1, -0.5).asDiagonal() * r.transpose();
  EXPECT_NEAR((saddleShaped(weaker, shape, 1) - shape).norm(), 0, 1e-12);
  MetricOptions o;
  o.saddleShape = 1.5;
  EXPECT_THROW(validate(o), InputError);
}

TEST(MetricFromHessian, SaddleLatticeRowsMakeTheShapedTriangleRightIsosceles) {
  // H = R diag(1, −β) Rᵀ, β = 0.8 (a saddle, not harmonic) and the loop's shape exponent 1.05:
  // the metric-equilateral triangle of M = S^½ C S^½ with its base along the row t is, in
  // y = S^½ x, right isosceles with its right angle at the apex and its legs along H's
  // eigenvectors (the P1 triangle of least H1 error for the harmonic saddle of y). Row weight
  // 1 there, 0 on a definite Hessian, on a saddle with |r| < 0.55, or with saddleShape 0.
  const double t = 0.3, c = std::cos(t), s = std::sin(t), beta = 0.8, expo = 1.05;
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  const Hessian2 h = r * Eigen::Vector2d(1, -beta).asDiagonal() * r.transpose();
  const Hessian2 shape = r * Eigen::Vector2d(1, std::pow(beta, expo)).asDiagonal() * r.transpose();
  MetricOptions o;
  o.shapeBlend = expo - 1;
  o.saddleShape = 1;
  const Hessian2 definite = r * Eigen::Vector2d(2, 1).asDiagonal() * r.transpose();
  const Hessian2 flat = r * Eigen::Vector2d(1, -0.5).asDiagonal() * r.transpose();
  const std::vector<Hessian2> hs{h, definite, flat};
  const auto rows = saddleLatticeRows(hs, o);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_NEAR(rows[0].norm(), 1, 1e-12);
  EXPECT_EQ(rows[1].norm(), 0);
  EXPECT_EQ(rows[2].norm(), 0);
  o.saddleShape = 0;
  EXPECT_EQ(saddleLatticeRows(hs, o)[0].norm(), 0);

  const double alpha = 0.5 * std::atan2(rows[0].y(), rows[0].x());
  const Eigen::Vector2d dir(std::cos(alpha), std::sin(alpha));
  const Hessian2 m = saddleShaped(h, shape, 1);
  const auto root = [](const Eigen::Matrix2d& a, double power) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(a);
    return Eigen::Matrix2d(es.eigenvectors() * es.eigenvalues().array().pow(power).matrix().asDiagonal() *
                           es.eigenvectors().transpose());
  };
  // Base 0 → b (b along t), apex at b/2 + (√3/2) × b turned by 90° in metric space.
  const Eigen::Vector2d base = root(m, 0.5) * dir;
  const Eigen::Vector2d apexMetric = 0.5 * base + 0.5 * std::sqrt(3.0) * Eigen::Vector2d(-base.y(), base.x());
  const Eigen::Matrix2d toY = root(shape, 0.5) * root(m, -0.5);  // metric space → y = S^½ x
  const Eigen::Vector2d b = toY * base, p = toY * apexMetric;
  const Eigen::Vector2d leg1 = p, leg2 = p - b;
  EXPECT_NEAR(leg1.dot(leg2) / leg1.squaredNorm(), 0, 1e-9);      // right angle at the apex
  EXPECT_NEAR(leg2.squaredNorm() / leg1.squaredNorm(), 1, 1e-9);  // isosceles
  const double along = std::max(std::abs(leg1.normalized().dot(r.col(0))), std::abs(leg1.normalized().dot(r.col(1))));
  EXPECT_NEAR(along, 1, 1e-9);  // legs along H's eigenvectors
}

TEST(MetricFromHessian, SaddleSideFollowsTheWall) {
  // H = [[0, 1], [1, 0]] (the Hessian of u = xy, as at a Dirichlet wall of a harmonic u): C's
  // long axis is at +45° to e₊ = (1, 1)/√2, i.e. along y. At a wall along y it stays; at a wall
  // along x the other side is taken (long axis along x), the rows turn with it, and the
  // determinant is the same on both sides.
  Hessian2 h;
  h << 0, 1, 1, 0;
  const Hessian2 shape = Hessian2::Identity();
  const auto longAxis = [](const Hessian2& m) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m);
    return Eigen::Vector2d(es.eigenvectors().col(0));
  };
  const Hessian2 free = saddleShaped(h, shape, 1), alongY = saddleShaped(h, shape, 1, Vec2(0, 1));
  const Hessian2 alongX = saddleShaped(h, shape, 1, Vec2(1, 0));
  EXPECT_NEAR(std::abs(longAxis(free).y()), 1, 1e-9);
  EXPECT_NEAR((alongY - free).norm(), 0, 1e-12);
  EXPECT_NEAR(std::abs(longAxis(alongX).x()), 1, 1e-9);
  EXPECT_NEAR(alongX.determinant(), free.determinant(), 1e-12);
  MetricOptions o;
  o.saddleShape = 1;
  o.shapeBlend = 0;
  const std::vector<Hessian2> hs{h, h, h};
  const std::vector<Vec2> walls{Vec2::Zero(), Vec2(0, 1), Vec2(1, 0)};
  const auto rows = saddleLatticeRows(hs, o, walls);
  EXPECT_NEAR(rows[0].x(), -1, 1e-9);  // row along y: (cos 2α, sin 2α) = (−1, 0)
  EXPECT_NEAR(rows[1].x(), -1, 1e-9);
  EXPECT_NEAR(rows[2].x(), 1, 1e-9);  // row along x
}

TEST(MetricFromHessian, WallTangentsAreZeroInsideAndAtCorners) {
  const Mesh2 mesh = fem::unitSquareMesh(4);
  const auto t = wallTangents(mesh);
  int sides = 0;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 p = mesh.vertices[v];
    const bool onX = p.y() == 0 || p.y() == 1, onY = p.x() == 0 || p.x() == 1;
    if (onX && onY) {
      EXPECT_EQ(t[v].norm(), 0) << "corner " << p.transpose();
    } else if (onX || onY) {
      EXPECT_NEAR(std::abs(onX ? t[v].x() : t[v].y()), 1, 1e-12) << p.transpose();
      ++sides;
    } else {
      EXPECT_EQ(t[v].norm(), 0);
    }
  }
  EXPECT_EQ(sides, 12);
}

TEST(MetricFromHessian, SingularCornerGradingEndsTheGrading) {
  // L-shape, sizes h = A |x − x0|^σ (σ = ⅔: u ~ r^(2/3)) around x0, the corner's own size hc.
  // x0 = (0, 0), the reentrant corner: the grading's end is r* = A^(1/(1−σ)) = A³, and the corner
  // gets max(β r*, hc/4); every other vertex keeps its metric. x0 = (−1, −1), a convex corner:
  // nothing changes (no singularity there for smooth data).
  const Mesh2 mesh = fem::structuredMesh(fem::makeProblem("lshape").domain, 40, 40);
  const double a = 0.05, sigma = 2.0 / 3, rStar = a * a * a, beta = 0.25;
  const auto field = [&](Vec2 x0, double hc) {
    std::vector<Metric2> m(mesh.numVertices());
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double r = (mesh.vertices[v] - x0).norm();
      m[v] = Metric2::isotropic(r > 0 ? a * std::pow(r, sigma) : hc);
    }
    return m;
  };
  const auto size = [](const Metric2& m) { return std::pow(m.det(), -0.25); };
  int corner = -1;
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (mesh.vertices[v].norm() == 0) corner = v;
  ASSERT_GE(corner, 0);
  for (const double hc : {5e-5, 1e-3}) {
    auto m = field(Vec2::Zero(), hc);
    const auto before = m;
    EXPECT_EQ(gradeSingularCorners(mesh, m, beta, 0), 1);
    EXPECT_NEAR(size(m[corner]) / std::max(beta * rStar, 0.25 * hc), 1, 1e-6) << hc;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      if (v == corner) continue;
      EXPECT_EQ(size(m[v]), size(before[v]));
    }
  }
  auto fine = field(Vec2::Zero(), 1e-5);  // already below β r*: unchanged
  EXPECT_EQ(gradeSingularCorners(mesh, fine, beta, 0), 0);
  auto convex = field(Vec2(-1, -1), 1e-3);
  EXPECT_EQ(gradeSingularCorners(mesh, convex, beta, 0), 0);
  EXPECT_THROW(gradeSingularCorners(mesh, fine, 0, 0), InputError);
}
