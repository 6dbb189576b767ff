#include "ablmg/core/metric2.hpp"

#include "ablmg/core/error.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>

namespace ablmg {
namespace {

/// Symmetric eigen-decomposition of [a b; b c]: eigenvalues l1 ≤ l2 (ascending) and the
/// angle of the eigenvector of l1. Closed form, stable for b ≈ 0.
struct SymEig {
  double l1, l2, angle;
};

SymEig symEig(double a, double b, double c) {
  const double mean = 0.5 * (a + c);
  const double half = 0.5 * (a - c);
  const double r = std::hypot(half, b);
  SymEig e;
  e.l1 = mean - r;
  e.l2 = mean + r;
  // eigenvector of l1 = mean - r: angle φ with tan 2φ = 2b/(a−c), rotated by π/2 to pick l1
  e.angle = 0.5 * std::atan2(-2.0 * b, -(a - c));
  return e;
}

Metric2 fromEig(double l1, double l2, double angle) {
  const double cs = std::cos(angle), sn = std::sin(angle);
  return Metric2::raw(l1 * cs * cs + l2 * sn * sn, (l1 - l2) * cs * sn, l1 * sn * sn + l2 * cs * cs);
}

}  // namespace

Metric2 Metric2::fromSizes(double h1, double h2, double theta, const std::string& what) {
  ABLMG_REQUIRE(std::isfinite(h1) && std::isfinite(h2) && std::isfinite(theta),
                what << ": non-finite size or angle (h1=" << h1 << ", h2=" << h2 << ", theta=" << theta << ")");
  ABLMG_REQUIRE(h1 > 0 && h2 > 0, what << ": sizes must be positive (h1=" << h1 << ", h2=" << h2 << ")");
  const Metric2 m = fromEig(1.0 / (h1 * h1), 1.0 / (h2 * h2), theta);
  ABLMG_REQUIRE(m.isSpd(),
                what << ": sizes (h1=" << h1 << ", h2=" << h2 << ") give a tensor that is not numerically SPD");
  return m;
}

Metric2 Metric2::fromTensor(double m11, double m12, double m22, const std::string& what) {
  const Metric2 m = raw(m11, m12, m22);
  ABLMG_REQUIRE(std::isfinite(m11) && std::isfinite(m12) && std::isfinite(m22),
                what << ": non-finite tensor (" << m11 << ", " << m12 << ", " << m22 << ")");
  // An SPD tensor whose eigenvalue ratio passes ~1e16 (sizes 1e8 apart) has its smaller
  // eigenvalue lost to round-off: said so, not "not positive definite".
  ABLMG_REQUIRE(m.isSpd() || !(m11 > 0 && m22 > 0 && m11 * m22 - m12 * m12 > 0),
                what << ": tensor (" << m11 << ", " << m12 << ", " << m22
                     << ") is too anisotropic: its smaller eigenvalue is lost to round-off");
  ABLMG_REQUIRE(m.isSpd(), what << ": tensor (" << m11 << ", " << m12 << ", " << m22 << ") is not positive definite");
  return m;
}

bool Metric2::isSpd() const {
  if (!(std::isfinite(a_) && std::isfinite(b_) && std::isfinite(c_))) return false;
  if (!(a_ > 0 && c_ > 0)) return false;
  const SymEig e = symEig(a_, b_, c_);
  return e.l1 > 0 && std::isfinite(1.0 / e.l1) && std::isfinite(e.l2);
}

MetricEigen Metric2::eigen() const {
  const SymEig e = symEig(a_, b_, c_);
  double theta = e.angle;  // direction of the smallest eigenvalue = largest size h1
  const double pi = std::numbers::pi;
  while (theta < 0) theta += pi;
  while (theta >= pi) theta -= pi;
  return {1.0 / std::sqrt(e.l1), 1.0 / std::sqrt(e.l2), theta};
}

double Metric2::length(const Vec2& v) const { return std::sqrt(std::max(0.0, squaredLength(v))); }

double Metric2::ellipseRadius(const Vec2& dir) const { return std::sqrt(dir.squaredNorm() / squaredLength(dir)); }

Metric2 Metric2::logm() const {
  const SymEig e = symEig(a_, b_, c_);
  return fromEig(std::log(e.l1), std::log(e.l2), e.angle);
}

Metric2 Metric2::expm() const {
  // Closed form for a symmetric 2×2 L = m·I + N (m = tr L / 2, N traceless with N² = δ² I):
  // exp(L) = e^m (cosh δ · I + (sinh δ / δ) · N). No eigenvectors, so no atan2/sincos (this
  // runs once per bubble per dynamics step under a background metric).
  const double m = 0.5 * (a_ + c_), h = 0.5 * (a_ - c_);
  const double delta = std::sqrt(h * h + b_ * b_);
  const double em = std::exp(m);
  if (!(delta > 1e-8)) {  // sinh δ / δ = 1 + δ²/6 + …; cosh δ = 1 + δ²/2 + …
    const double s = em * (1 + delta * delta / 6), c = em * (1 + 0.5 * delta * delta);
    return raw(c + s * h, s * b_, c - s * h);
  }
  const double ep = std::exp(delta), en = 1.0 / ep;
  const double c = em * 0.5 * (ep + en), s = em * 0.5 * (ep - en) / delta;
  return raw(c + s * h, s * b_, c - s * h);
}

Metric2 logEuclideanMean(std::span<const Metric2> metrics, std::span<const double> weights) {
  ABLMG_ASSERT(metrics.size() == weights.size() && !metrics.empty(), "");
  double a = 0, b = 0, c = 0, wsum = 0;
  bool allSame = true;
  for (std::size_t k = 0; k < metrics.size(); ++k) {
    if (weights[k] == 0.0) continue;
    allSame = allSame && metrics[k].m11() == metrics[0].m11() && metrics[k].m12() == metrics[0].m12() &&
              metrics[k].m22() == metrics[0].m22();
    const Metric2 l = metrics[k].logm();
    a += weights[k] * l.m11();
    b += weights[k] * l.m12();
    c += weights[k] * l.m22();
    wsum += weights[k];
  }
  ABLMG_ASSERT(wsum > 0, "all interpolation weights are zero");
  if (allSame) return metrics[0];  // exact reproduction of a constant field
  return Metric2::raw(a / wsum, b / wsum, c / wsum).expm();
}

Metric2 intersect(const Metric2& x, const Metric2& y) {
  // Simultaneous reduction: N = X⁻¹ Y has real eigenvectors P (X-orthogonal); in that basis
  // both are diagonal and the intersection takes the larger eigenvalue per direction.
  const Eigen::Matrix2d X{{x.m11(), x.m12()}, {x.m12(), x.m22()}};
  const Eigen::Matrix2d Y{{y.m11(), y.m12()}, {y.m12(), y.m22()}};
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> ges(Y, X);  // Y p = μ X p
  const Eigen::Matrix2d P = ges.eigenvectors();                         // Pᵀ X P = I
  Eigen::Matrix2d D = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 2; ++k) D(k, k) = std::max(1.0, ges.eigenvalues()(k));  // Pᵀ Y P = diag(μ)
  const Eigen::Matrix2d Pinv = P.inverse();
  const Eigen::Matrix2d R = Pinv.transpose() * D * Pinv;
  return Metric2::raw(R(0, 0), 0.5 * (R(0, 1) + R(1, 0)), R(1, 1));
}

double edgeLength(const Vec2& a, const Metric2& ma, const Vec2& b, const Metric2& mb) {
  const Vec2 e = b - a;
  const double la = ma.length(e), lb = mb.length(e);
  // Size h(t) interpolated linearly from |e|/la to |e|/lb: ∫ |e|/h(t) dt in closed form.
  const double r = la / lb;
  if (std::abs(r - 1.0) < 1e-6) return 0.5 * (la + lb);
  return la * lb * std::log(r) / (la - lb);
}

}  // namespace ablmg
