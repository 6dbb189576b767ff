#pragma once
/// Metric2: a symmetric positive-definite 2×2 Riemannian metric tensor (paper eq. 1–2).
///
///   M = [m11 m12; m12 m22] = R(θ) diag(1/h1², 1/h2²) R(θ)ᵀ,
///
/// h1, h2 are the prescribed edge lengths (units of the domain's coordinates) along the
/// eigenvectors e1 = (cos θ, sin θ) and e2 = (−sin θ, cos θ). A vector v has metric length
/// |v|_M = sqrt(vᵀ M v) (dimensionless; 1 means "exactly the prescribed size").
/// The unit ball {v : vᵀ M v ≤ 1} is the ellipse with semi-axes h1, h2 rotated by θ.
///
/// Invariant: every Metric2 that exists is SPD with finite entries; the factory functions
/// throw ablmg::InputError otherwise (message names the values).
#include "ablmg/core/vec2.hpp"

#include <span>
#include <string>

namespace ablmg {

struct MetricEigen {
  double h1, h2;  ///< sizes along e1, e2 (h = 1/sqrt(λ)), h1 ≥ h2 > 0
  double theta;   ///< angle of e1 with the x axis, in [0, π)
};

class Metric2 {
 public:
  /// The identity (h1 = h2 = 1).
  Metric2() = default;
  /// From sizes and angle (eq. 2); h1, h2 > 0 and finite. `what` prefixes error messages.
  static Metric2 fromSizes(double h1, double h2, double theta, const std::string& what = "metric");
  /// From tensor entries (eq. 1); must be SPD and finite.
  static Metric2 fromTensor(double m11, double m12, double m22, const std::string& what = "metric");
  /// Isotropic metric of size h: M = I / h².
  static Metric2 isotropic(double h) { return fromSizes(h, h, 0.0); }

  double m11() const { return a_; }
  double m12() const { return b_; }
  double m22() const { return c_; }
  double det() const { return a_ * c_ - b_ * b_; }

  /// Eigen-decomposition as sizes and angle; h1 ≥ h2.
  MetricEigen eigen() const;

  /// vᵀ M v.
  double squaredLength(const Vec2& v) const { return a_ * v.x() * v.x() + 2 * b_ * v.x() * v.y() + c_ * v.y() * v.y(); }
  /// Metric length sqrt(vᵀ M v) (eq. 3 with M the averaged tensor).
  double length(const Vec2& v) const;
  /// uᵀ M v.
  double dot(const Vec2& u, const Vec2& v) const {
    return a_ * u.x() * v.x() + b_ * (u.x() * v.y() + u.y() * v.x()) + c_ * u.y() * v.y();
  }
  /// Euclidean distance from the centre to the boundary of the unit-metric ellipse along the
  /// non-zero direction `dir` (|dir| / sqrt(dirᵀ M dir)); no trigonometry. The bubble of a
  /// node is this ellipse scaled by 1/2, so l_ij of eq. (8) is 0.5 * ellipseRadius(x_j − x_i).
  double ellipseRadius(const Vec2& dir) const;

  /// Matrix logarithm/exponential (symmetric); used by log-Euclidean interpolation.
  Metric2 logm() const;  ///< result is symmetric but not necessarily SPD: use only with expm
  Metric2 expm() const;

  /// Entry-wise affine combination (not necessarily SPD for negative weights).
  friend Metric2 operator+(const Metric2& x, const Metric2& y) { return raw(x.a_ + y.a_, x.b_ + y.b_, x.c_ + y.c_); }
  friend Metric2 operator*(double s, const Metric2& x) { return raw(s * x.a_, s * x.b_, s * x.c_); }

  bool isSpd() const;
  /// Construct without checks (internal use: results of operations proven SPD).
  static Metric2 raw(double m11, double m12, double m22) {
    Metric2 m;
    m.a_ = m11;
    m.b_ = m12;
    m.c_ = m22;
    return m;
  }

 private:
  double a_ = 1.0, b_ = 0.0, c_ = 1.0;
};

/// Arithmetic mean (M_x + M_y)/2 — the M_avg of eq. (3).
inline Metric2 average(const Metric2& x, const Metric2& y) { return 0.5 * (x + y); }

/// Log-Euclidean interpolation exp(Σ w_k log M_k) / Σ w_k. Weights ≥ 0, not all zero.
/// Reproduces a constant field exactly (up to round-off) and always returns an SPD tensor.
Metric2 logEuclideanMean(std::span<const Metric2> metrics, std::span<const double> weights);

/// Metric intersection (the largest ellipse inside both unit balls; the smaller sizes in every
/// direction), by simultaneous reduction. Commutative; intersect(M, M) == M.
Metric2 intersect(const Metric2& x, const Metric2& y);

/// Metric length of the segment a→b integrated along it, with the metric linearly
/// interpolated in its inverse-sqrt (Simpson rule on the length); for a constant metric
/// this equals eq. (3) exactly.
double edgeLength(const Vec2& a, const Metric2& ma, const Vec2& b, const Metric2& mb);

}  // namespace ablmg
