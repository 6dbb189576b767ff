#pragma once
/// MetricField: the prescribed Riemannian metric M(x) over the plane (paper §2).
///
/// Implementations:
///  - ConstantMetricField: one tensor everywhere.
///  - AnalyticMetricField: muparser expressions in x, y giving either (h1, h2, theta) or
///    (m11, m12, m22) (eq. 1 or 2). Expressions are checked when the field is built (unknown
///    variables, syntax) and every evaluation is checked for SPD (the error names the point).
///    Defined in core/analytic_metric_field.cpp, target ablmg_expr (ablmg::expr: links muparser);
///    the rest of this header is ablmg_core's.
///  - BackgroundMetricField: per-vertex tensors on a triangle mesh, interpolated
///    log-Euclidean with barycentric weights (interpolating log M keeps the result SPD and
///    does not inflate sizes the way linear interpolation of M⁻¹ or M does). Point location:
///    grid start + walk, hint-accelerated. Outside the mesh: nearest-triangle extrapolation.
///
/// Thread safety: `at()` of an AnalyticMetricField is not thread-safe (muparser state);
/// call `evaluate()` from one thread. The others are read-only and thread-safe.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include "ablmg/core/point_locator.hpp"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace ablmg {

class MetricField {
 public:
  virtual ~MetricField() = default;
  /// M at point p.
  virtual Metric2 at(const Vec2& p) const = 0;
  /// M at many points (out.size() == points.size()); override for speed.
  virtual void evaluate(std::span<const Vec2> points, std::span<Metric2> out) const;
  /// The same, with one location hint per point (in: where the point was last, −1 = unknown;
  /// out: where it is now). Fields without a mesh ignore the hints. Used by the bubble
  /// dynamics, whose bubbles move a little between evaluations.
  virtual void evaluate(std::span<const Vec2> points, std::span<Metric2> out, std::span<int> hints) const;
  /// √det M at many points (out.size() == points.size()): the density of the metric's area,
  /// ∫ √det M dA, which sizes the node count. The default evaluates M; a background field
  /// needs no tensor (see there).
  virtual void sqrtDeterminants(std::span<const Vec2> points, std::span<double> out) const;
  /// √det M at the centres lo + ((x + ½) d.x, (y + ½) d.y) of the cells of a gx × gy grid whose
  /// `mask[y gx + x]` is set, into out[y gx + x] (other entries untouched; mask and out hold
  /// gx gy entries). The default calls sqrtDeterminants on those centres in raster order; a
  /// background field rasterises its triangles onto the grid (see there).
  virtual void gridSqrtDeterminants(const Vec2& lo, const Vec2& d, int gx, int gy, std::span<const char> mask,
                                    std::span<double> out) const;
  /// True if at() is the same everywhere (lets the mesher skip re-evaluation).
  virtual bool isConstant() const { return false; }
  /// True if at() and evaluate() may be called from several threads at once (the mesher then
  /// grows large initial lattices in parallel bands). Default false: a field of the caller's
  /// own is evaluated from one thread.
  virtual bool isThreadSafe() const { return false; }
  /// True if the field carries lattice rows (latticeRow below).
  virtual bool hasLatticeRows() const { return false; }
  /// The lattice row hint at p: w (cos 2α, sin 2α), w ∈ [0, 1] the weight with which the
  /// mesher's initial lattice runs a row along the physical direction (cos α, sin α) (α mod π:
  /// the doubled angle makes the hint interpolable), 0 = no preference (the mesher's own
  /// orientation, mesher::LatticeOrientation). `hint` as in evaluate(). Default: 0.
  virtual Vec2 latticeRow(const Vec2& p, int& hint) const;
};

class ConstantMetricField final : public MetricField {
 public:
  explicit ConstantMetricField(const Metric2& m) : m_(m) {}
  Metric2 at(const Vec2&) const override { return m_; }
  bool isConstant() const override { return true; }
  bool isThreadSafe() const override { return true; }

 private:
  Metric2 m_;
};

class AnalyticMetricField final : public MetricField {
 public:
  enum class Form { Sizes, Tensor };  ///< (h1, h2, theta) or (m11, m12, m22)
  /// Throws InputError naming `source` (e.g. "config.json: metric.h1") on a bad expression.
  AnalyticMetricField(Form form, const std::string& e1, const std::string& e2, const std::string& e3,
                      const std::string& source = "metric");
  ~AnalyticMetricField() override;
  Metric2 at(const Vec2& p) const override;
  /// True when no expression uses x or y (then M is evaluated once, at construction).
  bool isConstant() const override;
  /// Only when constant: evaluating the expressions uses muparser's state.
  bool isThreadSafe() const override { return isConstant(); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class BackgroundMetricField final : public MetricField {
 public:
  /// Whether the constructor runs Mesh2::validate() on the mesh (the default), or the caller
  /// has just done so on this very mesh and it passed (the remesh command validates its input
  /// as it reads it: the check is not repeated).
  enum class MeshCheck { Validate, AlreadyValidated };
  /// mesh must be valid; metrics.size() == mesh.numVertices(). Copies both.
  BackgroundMetricField(Mesh2 mesh, std::vector<Metric2> metrics, MeshCheck check = MeshCheck::Validate);
  /// With per-vertex lattice rows (latticeRow; rows.size() == mesh.numVertices(), each of norm
  /// ≤ 1, or empty = none), interpolated linearly with the barycentric weights.
  BackgroundMetricField(Mesh2 mesh, std::vector<Metric2> metrics, std::vector<Vec2> rows,
                        MeshCheck check = MeshCheck::Validate);
  bool isThreadSafe() const override { return true; }
  bool hasLatticeRows() const override { return !rows_.empty(); }
  Vec2 latticeRow(const Vec2& p, int& hint) const override;
  Metric2 at(const Vec2& p) const override;
  void evaluate(std::span<const Vec2> points, std::span<Metric2> out) const override;
  /// Hint = triangle index; points are located in parallel (OpenMP), each from its own hint
  /// (without one, −1: the previous answer of its chunk of 256 consecutive points) or from the
  /// grid, whichever is nearer (PointLocator::startNear).
  void evaluate(std::span<const Vec2> points, std::span<Metric2> out, std::span<int> hints) const override;
  /// det exp(L) = exp(tr L) and tr L is linear in the barycentric weights, so √det M at a point
  /// is exp(½ Σ wₖ tr log Mₖ): no tensor exponential. Points are located in fixed chunks of
  /// consecutive points, each from the previous point's triangle (neighbours on a raster row
  /// share triangles), the chunks in parallel (OpenMP; the same values for any thread count).
  void sqrtDeterminants(std::span<const Vec2> points, std::span<double> out) const override;
  /// Each triangle visits the grid cells of its bounding box and takes the centres it contains
  /// (exact orientation tests; a centre on a shared edge goes to the lowest triangle), with the
  /// barycentric weights and the sum of sqrtDeterminants, so a centre inside a triangle gets the
  /// same bits as there; centres no triangle holds (outside the mesh) go to sqrtDeterminants.
  /// O(cells + triangles), where locating each centre cost a walk (several times more); bands of
  /// grid rows in parallel (OpenMP; the same values for any thread count).
  void gridSqrtDeterminants(const Vec2& lo, const Vec2& d, int gx, int gy, std::span<const char> mask,
                            std::span<double> out) const override;
  const Mesh2& mesh() const { return mesh_; }
  const std::vector<Metric2>& metrics() const { return metrics_; }

 private:
  Metric2 interpolate(const PointLocator::Location& loc) const;
  Mesh2 mesh_;
  std::vector<Metric2> metrics_;
  std::vector<Metric2> logs_;  ///< log M per vertex, precomputed
  std::vector<Vec2> rows_;     ///< lattice row per vertex (empty: none)
  std::unique_ptr<PointLocator> locator_;
};

}  // namespace ablmg
