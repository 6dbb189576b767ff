#include "ablmg/adapt/metric_from_hessian.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace ablmg::adapt {
namespace {
/// Below this many vertices the per-vertex loops run on the calling thread (waking a team costs
/// more than a few thousand 2×2 eigen-decompositions).
constexpr int kMinParallelVertices = 4096;
}  // namespace

ErrorNorm parseErrorNorm(const std::string& name) {
  if (name == "l2") return ErrorNorm::L2;
  if (name == "h1") return ErrorNorm::H1;
  ABLMG_REQUIRE(false, "unknown error norm '" << name << "' (valid: l2, h1)");
  return ErrorNorm::L2;
}

std::string toString(ErrorNorm norm) { return norm == ErrorNorm::L2 ? "l2" : "h1"; }

void validate(const MetricOptions& o) {
  ABLMG_REQUIRE(std::isfinite(o.targetVertices) && o.targetVertices > 0,
                "metric options: targetVertices must be > 0 (got " << o.targetVertices << ")");
  ABLMG_REQUIRE(o.p >= 1, "metric options: p must be >= 1 or inf (got " << o.p << ")");
  ABLMG_REQUIRE(o.hmin >= 0 && std::isfinite(o.hmin), "metric options: hmin must be >= 0 (got " << o.hmin << ")");
  ABLMG_REQUIRE(o.hmax > o.hmin,
                "metric options: hmax must be > hmin (got hmax " << o.hmax << ", hmin " << o.hmin << ")");
  ABLMG_REQUIRE(o.maxAnisotropy >= 1, "metric options: maxAnisotropy must be >= 1 (got " << o.maxAnisotropy << ")");
  ABLMG_REQUIRE(o.norm == ErrorNorm::L2 || o.norm == ErrorNorm::H1, "metric options: unknown norm " << int(o.norm));
  ABLMG_REQUIRE(!o.shapeBlend || (*o.shapeBlend >= 0 && *o.shapeBlend <= 1),
                "metric options: shapeBlend must be in [0, 1] (got " << o.shapeBlend.value_or(0) << ")");
  ABLMG_REQUIRE(o.saddleShape >= 0 && o.saddleShape <= 1,
                "metric options: saddleShape must be in [0, 1] (got " << o.saddleShape << ")");
  ABLMG_REQUIRE(o.hmaxUniform > 0, "metric options: hmaxUniform must be > 0 or inf (got " << o.hmaxUniform << ")");
  ABLMG_REQUIRE(o.eigenFloor > 0 && o.eigenFloor < 1,
                "metric options: eigenFloor must be in (0, 1) (got " << o.eigenFloor << ")");
}

Hessian2 absoluteHessian(const Hessian2& h, double floor) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
  es.computeDirect(h);
  Eigen::Vector2d l = es.eigenvalues().cwiseAbs();
  l = l.cwiseMax(floor);
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}

namespace {
/// The saddle weight of MetricOptions::saddleShape: 0 up to −r = 0.55, 1 from 0.65 on.
double saddleWeight(double ratio) { return std::clamp((-ratio - 0.55) / 0.1, 0.0, 1.0); }

/// True when C's long axis at +45° from `pos` is closer to the normal of `wall` than to it
/// (the side at −45° is then the one along the wall); false for wall = 0 (not on a wall).
bool wallFlip(const Vec2& pos, const Vec2& wall) {
  if (wall.squaredNorm() == 0) return false;
  const Vec2 c1 = (pos + Vec2(-pos.y(), pos.x())) / std::sqrt(2.0);
  return std::abs(c1.dot(wall)) < std::abs(c1.x() * wall.y() - c1.y() * wall.x());
}

/// Per vertex: 0 interior, 1 on a straight (turn ≤ 20°) stretch of the boundary, 2 at a convex
/// corner, 3 at a reentrant one (interior angle > π: the boundary turns right, the domain being on
/// its left, or turns back on itself as at a slit's tip); `tangent` gets the mean unit tangent of
/// the boundary edges at kind-1 vertices (0 elsewhere).
std::vector<char> boundaryKinds(const Mesh2& mesh, std::vector<Vec2>& tangent) {
  const int n = mesh.numVertices();
  std::vector<Vec2> in(n, Vec2::Zero()), out(n, Vec2::Zero());
  for (const auto& e : mesh.boundaryEdges) {
    const Vec2 d = (mesh.vertices[e.b] - mesh.vertices[e.a]).normalized();
    out[e.a] = d;
    in[e.b] = d;
  }
  std::vector<char> kind(n, 0);
  tangent.assign(n, Vec2::Zero());
  const double cosTurn = std::cos(20 * std::numbers::pi / 180);
  for (int v = 0; v < n; ++v) {
    if (in[v].squaredNorm() == 0 && out[v].squaredNorm() == 0) continue;
    const double dot = in[v].dot(out[v]), cross = in[v].x() * out[v].y() - in[v].y() * out[v].x();
    if (in[v].squaredNorm() == 0 || out[v].squaredNorm() == 0 || dot >= cosTurn) {
      kind[v] = 1;
      tangent[v] = (in[v] + out[v]).normalized();
    } else {
      kind[v] = cross < 0 || dot < -0.99 ? 3 : 2;
    }
  }
  return kind;
}
}  // namespace

std::vector<Vec2> wallTangents(const Mesh2& mesh) {
  std::vector<Vec2> tangent;
  boundaryKinds(mesh, tangent);
  return tangent;
}

int gradeSingularCorners(const Mesh2& mesh, std::vector<Metric2>& metric, double beta, double hmin) {
  const int n = mesh.numVertices();
  ABLMG_REQUIRE(beta > 0 && beta <= 1, "gradeSingularCorners: beta must be in (0, 1] (got " << beta << ")");
  ABLMG_REQUIRE(long(metric.size()) == long(n),
                "gradeSingularCorners: " << metric.size() << " metrics for " << n << " vertices");
  std::vector<Vec2> tangent;
  const std::vector<char> kind = boundaryKinds(mesh, tangent);
  if (std::find(kind.begin(), kind.end(), char(3)) == kind.end()) return 0;
  // Edge lists in triangle order (duplicates included): the rings' order, and so the fit's sums,
  // follow it.
  std::vector<std::vector<int>> adj(n);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) adj[t[k]].push_back(t[(k + 1) % 3]), adj[t[(k + 1) % 3]].push_back(t[k]);
  std::vector<int> seen(n, -1);
  int graded = 0;
  for (int c = 0; c < n; ++c) {
    if (kind[c] != 3) continue;
    // Rings 3–6 around c (the inner rings' recovered Hessians are patch averages over the
    // corner): log h against log r, h = det(M)^(−1/4).
    std::vector<int> ring{c}, all;
    seen[c] = c;
    for (int k = 0; k < 6; ++k) {
      std::vector<int> next;
      for (const int v : ring)
        for (const int w : adj[v])
          if (seen[w] != c) seen[w] = c, next.push_back(w);
      if (k >= 2) all.insert(all.end(), next.begin(), next.end());
      ring = std::move(next);
    }
    if (all.size() < 6) continue;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const int v : all) {
      const double x = std::log((mesh.vertices[v] - mesh.vertices[c]).norm()), y = -0.25 * std::log(metric[v].det());
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double m = double(all.size()), var = sxx - sx * sx / m;
    if (!(var > 0)) continue;
    const double sigma = (sxy - sx * sy / m) / var, logA = (sy - sigma * sx) / m;
    if (!(sigma > 0.2 && sigma < 0.95)) continue;  // no singular growth of |H| towards c
    const double hc = std::pow(metric[c].det(), -0.25);
    const double rStar = std::max({beta * std::exp(logA / (1 - sigma)), 0.25 * hc, hmin});
    if (!(rStar < hc)) continue;
    metric[c] = intersect(metric[c], Metric2::isotropic(rStar));
    ++graded;
  }
  return graded;
}

Hessian2 saddleShaped(const Hessian2& h, const Hessian2& s, double sigma, const Vec2& wall) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> hs;
  hs.computeDirect(h);
  const Eigen::Vector2d e = hs.eigenvalues();  // ascending
  if (!(e[0] < 0 && e[1] > 0)) return s;       // definite or rank one: unchanged
  // r = −(smaller |λ|)/(larger |λ|) ∈ [−1, 0): −1 harmonic; the weight vanishes at rank one.
  const double r = -std::min(-e[0], e[1]) / std::max(-e[0], e[1]);
  const double f = std::pow(3.0, 0.25 * sigma * saddleWeight(r));  // √(aspect)
  const Eigen::Vector2d pos = hs.eigenvectors().col(1);
  const double side = wallFlip(pos, wall) ? -1 : 1;
  const double angle = std::atan2(pos.y(), pos.x()) + side * std::numbers::pi / 4;  // long axis
  Eigen::Matrix2d rot;
  rot << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const Eigen::Matrix2d c = rot * Eigen::Vector2d(1 / (f * f), f * f).asDiagonal() * rot.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> ss;
  ss.computeDirect(s);
  const Eigen::Matrix2d root =
      ss.eigenvectors() * ss.eigenvalues().cwiseSqrt().asDiagonal() * ss.eigenvectors().transpose();
  return root * c * root;
}

std::vector<Vec2> saddleLatticeRows(std::span<const Hessian2> hessians, const MetricOptions& o,
                                    std::span<const Vec2> walls) {
  std::vector<Vec2> rows(hessians.size(), Vec2::Zero());
  if (o.saddleShape <= 0) return rows;
  const double expo = 1 + o.shapeBlend.value_or(o.norm == ErrorNorm::H1 ? 1.0 : 0.0);
  for (std::size_t v = 0; v < hessians.size(); ++v) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> hs;
    hs.computeDirect(hessians[v]);
    const Eigen::Vector2d e = hs.eigenvalues();  // ascending
    if (!(e[0] < 0 && e[1] > 0)) continue;
    const double r = -std::min(-e[0], e[1]) / std::max(-e[0], e[1]);
    const double w = saddleWeight(r);
    if (w == 0) continue;
    const Vec2 pos = hs.eigenvectors().col(1), perp(-pos.y(), pos.x());
    const double side = !walls.empty() && wallFlip(pos, walls[v]) ? -1 : 1;
    const Vec2 t = pos * std::pow(e[1], -0.5 * expo) + side * perp * std::pow(-e[0], -0.5 * expo);
    const double alpha = std::atan2(t.y(), t.x());
    rows[v] = w * Vec2(std::cos(2 * alpha), std::sin(2 * alpha));
  }
  return rows;
}

double complexityForVertices(double vertices) { return 0.5 * std::sqrt(3.0) * vertices; }

Metric2 boundMetric(const Metric2& m, double hmin, double hmax, double maxAnisotropy) {
  Eigen::Matrix2d a;
  a << m.m11(), m.m12(), m.m12(), m.m22();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
  es.computeDirect(a);
  Eigen::Vector2d l = es.eigenvalues();  // ascending: l[0] ↔ largest size
  const double lmax = hmin > 0 ? 1.0 / (hmin * hmin) : std::numeric_limits<double>::infinity();
  const double lmin = std::isfinite(hmax) ? 1.0 / (hmax * hmax) : 0.0;
  for (int k = 0; k < 2; ++k) l[k] = std::clamp(l[k], lmin, lmax);
  // h1/h2 = sqrt(l1/l0) ≤ r  ⇔  l0 ≥ l1 / r²: raise the smaller eigenvalue (coarser size shrinks).
  l[0] = std::max(l[0], l[1] / (maxAnisotropy * maxAnisotropy));
  const Eigen::Matrix2d r = es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
  return Metric2::fromTensor(r(0, 0), 0.5 * (r(0, 1) + r(1, 0)), r(1, 1), "boundMetric");
}

double metricComplexity(const Mesh2& mesh, std::span<const Metric2> metrics) {
  ABLMG_REQUIRE(long(metrics.size()) == long(mesh.numVertices()),
                "metricComplexity: " << metrics.size() << " metrics for " << mesh.numVertices() << " vertices");
  std::vector<double> s(metrics.size());
  for (std::size_t v = 0; v < metrics.size(); ++v) s[v] = std::sqrt(std::max(metrics[v].det(), 0.0));
  double c = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    c += mesh.triangleArea(t) * (s[tri[0]] + s[tri[1]] + s[tri[2]]) / 3.0;
  }
  return c;
}

double effectiveHmax(const Mesh2& mesh, const MetricOptions& o) {
  if (!std::isfinite(o.hmaxUniform)) return o.hmax;
  double area = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) area += mesh.triangleArea(t);
  const double hN = std::sqrt(2 * area / (std::sqrt(3.0) * o.targetVertices));
  return std::max(std::min(o.hmax, o.hmaxUniform * hN), 2 * o.hmin);
}

namespace {
double integrate(const Mesh2& mesh, const std::vector<double>& s) {
  double c = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    c += mesh.triangleArea(t) * (s[tri[0]] + s[tri[1]] + s[tri[2]]) / 3.0;
  }
  return c;
}
}  // namespace

std::vector<Metric2> metricFromHessians(const Mesh2& mesh, std::span<const Hessian2> hessians, const MetricOptions& o) {
  validate(o);
  const int n = mesh.numVertices();
  ABLMG_REQUIRE(long(hessians.size()) == long(n),
                "metricFromHessians: " << hessians.size() << " Hessians for " << n << " vertices");
  double hmaxAbs = 0;
  for (int v = 0; v < n; ++v) {
    ABLMG_REQUIRE(hessians[v].allFinite(), "metricFromHessians: Hessian at vertex " << v << " is not finite");
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
    es.computeDirect(hessians[v]);
    hmaxAbs = std::max(hmaxAbs, es.eigenvalues().cwiseAbs().maxCoeff());
  }
  // A field with H ≡ 0 (u linear): any isotropic metric is optimal; use the identity shape.
  const double floor = hmaxAbs > 0 ? o.eigenFloor * hmaxAbs : 1.0;
  // Unscaled metric S(x) = det|H|^δ · (|H|/√det|H|)^s, so that M = D S and √det S = det|H|^δ:
  // L2 (Lp): δ = p/(2p+2), s = 1, i.e. S = det|H|^(−1/(2p+2)) |H|;  H1 (W^{1,p}): δ = p/(p+2),
  // s = 2, i.e. S = det|H|^(p/(p+2)) |H|²/det|H|;  p = ∞: δ = 1/2 (L2), 1 (H1);  s = 1 + shapeBlend if set.
  const bool pInf = std::isinf(o.p);
  const bool h1 = o.norm == ErrorNorm::H1;
  const double delta = h1 ? (pInf ? 1.0 : o.p / (o.p + 2)) : (pInf ? 0.5 : o.p / (2 * o.p + 2));
  const double s = 1 + o.shapeBlend.value_or(h1 ? 1.0 : 0.0);
  std::vector<Hessian2> shape(n);
  std::vector<double> sqrtDet(n);
  const std::vector<Vec2> walls = o.saddleShape > 0 ? wallTangents(mesh) : std::vector<Vec2>(n, Vec2::Zero());
  // Per vertex, independent: the same bits on any team size.
  ParallelFailure shapeFailure;
#pragma omp parallel for schedule(static) if (n >= kMinParallelVertices)
  for (int v = 0; v < n; ++v)
    shapeFailure.run(v, [&] {
      const Hessian2 a = absoluteHessian(hessians[v], floor);
      if (s == 1 && !h1) {  // the Lp metric, computed exactly as before the H1 option (bitwise same meshes)
        shape[v] = (pInf ? 1.0 : std::pow(a.determinant(), -1.0 / (2 * o.p + 2))) * a;
        sqrtDet[v] = std::sqrt(shape[v].determinant());
        if (o.saddleShape > 0) shape[v] = saddleShaped(hessians[v], shape[v], o.saddleShape, walls[v]);
        return;
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
      es.computeDirect(a);
      const Eigen::Vector2d l = es.eigenvalues();  // both ≥ floor > 0
      const double det = l[0] * l[1], root = std::sqrt(det), rho = std::pow(det, delta);
      const Eigen::Vector2d m(rho * std::pow(l[0] / root, s), rho * std::pow(l[1] / root, s));
      shape[v] = es.eigenvectors() * m.asDiagonal() * es.eigenvectors().transpose();
      sqrtDet[v] = std::sqrt(m[0] * m[1]);
      if (o.saddleShape > 0) shape[v] = saddleShaped(hessians[v], shape[v], o.saddleShape, walls[v]);
    });
  shapeFailure.rethrow();
  const double target = complexityForVertices(o.targetVertices);
  const double hmax = effectiveHmax(mesh, o);
  double d = target / integrate(mesh, sqrtDet);
  std::vector<Metric2> out(n);
  for (int it = 0; it < 60; ++it) {
    // Each vertex's bound is its own: the same bits on any team size (the sum below is serial).
    ParallelFailure failure;
#pragma omp parallel for schedule(static) if (n >= kMinParallelVertices)
    for (int v = 0; v < n; ++v)
      failure.run(v, [&] {
        const Hessian2 m = d * shape[v];
        out[v] = boundMetric(Metric2::raw(m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), m(1, 1)), o.hmin, hmax, o.maxAnisotropy);
      });
    failure.rethrow();
    const double c = metricComplexity(mesh, out);
    if (std::abs(c / target - 1) < 1e-4) break;
    // √det M scales like D where unbounded: a Newton-like fixed point on D.
    const double nd = d * target / c;
    if (!(nd > 0) || std::abs(nd / d - 1) < 1e-12) break;  // bounds saturate: closest value reached
    d = nd;
  }
  return out;
}

std::vector<Metric2> intersectFields(std::span<const Metric2> a, std::span<const Metric2> b) {
  ABLMG_REQUIRE(a.size() == b.size(), "intersectFields: sizes differ (" << a.size() << " vs " << b.size() << ")");
  std::vector<Metric2> out(a.size());
  const long n = long(a.size());
  ParallelFailure failure;
#pragma omp parallel for schedule(static) if (n >= kMinParallelVertices)
  for (long i = 0; i < n; ++i)
    failure.run(i, [&] { out[std::size_t(i)] = intersect(a[std::size_t(i)], b[std::size_t(i)]); });
  failure.rethrow();
  return out;
}

}  // namespace ablmg::adapt
