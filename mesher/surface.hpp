#pragma once
/// Parametric surface triangulation by the mapping method (paper §5–6).
///
///   r(u,v) ∈ ℝ³ over a parameter Domain;  M3 (3×3 SPD, eq. 14) prescribes sizes in 3D;
///   M2 = [r_u r_v]ᵀ M3 [r_u r_v]   (eq. 16)  — the induced metric in (u,v);
///   mesh the parameter domain with M2 (meshDomain), map the vertices back with r.
///
/// Units: (u,v) are the surface's parameters; lengths in 3D are the model's units.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric_field.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ablmg::mesher {

using Vec3 = Eigen::Vector3d;

class ParametricSurface {
 public:
  virtual ~ParametricSurface() = default;
  virtual Vec3 point(const Vec2& uv) const = 0;
  /// First derivatives r_u, r_v. Default: central differences with step 1e-6·(1+|u|) — the
  /// truncation error O(step²·|r'''|) ≈ 1e-12 and round-off ≈ 1e-10 relative; accepted
  /// because the induced metric needs only a few digits.
  virtual std::array<Vec3, 2> derivatives(const Vec2& uv) const;
  virtual const Domain& parameterDomain() const = 0;
  virtual std::string description() const = 0;
  /// True if r maps opposite sides of the parameter rectangle onto each other (a closed torus,
  /// a full cylinder): the mapped mesh is then welded along those seams (weldSeams).
  virtual bool periodic() const { return false; }
};

/// Names: paper-fig16, sphere-patch, torus, torus-closed, cylinder, saddle. Throws InputError otherwise.
std::unique_ptr<ParametricSurface> makeBuiltinSurface(const std::string& name);
/// One line per built-in: name, formula, parameter domain.
std::vector<std::string> builtinSurfaceList();
/// x(u,v), y(u,v), z(u,v) as muparser expressions over a rectangle [u0,u1]×[v0,v1];
/// `periodic`: r maps opposite sides onto each other, weld them (ParametricSurface::periodic).
/// Defined in mesher/expression_surface.cpp, target ablmg_expr (links muparser).
std::unique_ptr<ParametricSurface> makeExpressionSurface(const std::string& x, const std::string& y,
                                                         const std::string& z, double u0, double v0, double u1,
                                                         double v1, const std::string& source = "surface",
                                                         bool periodic = false);

/// The 3D metric field M3 (eq. 14); isotropic size h by default (eq. 17).
using Metric3 = Eigen::Matrix3d;
using Metric3Field = std::function<Metric3(const Vec3&)>;
Metric3Field isotropicMetric3(double h);

/// M2 = Jᵀ M3 J at (u,v) (eq. 16). A rank-deficient Jacobian (a pole, a fold) gives an
/// InputError naming (u,v) — never a NaN metric.
class InducedMetricField final : public MetricField {
 public:
  InducedMetricField(const ParametricSurface& surface, Metric3Field m3) : surface_(surface), m3_(std::move(m3)) {}
  Metric2 at(const Vec2& uv) const override;

 private:
  const ParametricSurface& surface_;
  Metric3Field m3_;
};

struct SurfaceMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< orientation of the parameter mesh
  double area() const;
};

/// Maps every vertex of the parameter mesh with r (same triangles); for a periodic() surface
/// the seams are then welded (weldSeams with a tolerance of 1e-9 × the bounding-box diagonal).
SurfaceMesh mapToSurface(const Mesh2& parameterMesh, const ParametricSurface& surface);

/// Merges vertices closer than `tolerance` in 3D (each into the lowest index of its group),
/// renumbers, and drops triangles that became degenerate. The seam's nodes coincide because
/// the boundary of the parameter rectangle is divided into equal metric lengths and r and M2
/// are periodic, so opposite sides get the same subdivision (to round-off).
SurfaceMesh weldSeams(const SurfaceMesh& mesh, double tolerance);

/// Lee's quality α of each triangle (eqs. 19–20) under M3. Eq. (20) is read with M_i
/// restricted to the triangle's plane (2×2, orthonormal basis) and with √det, so that a
/// triangle equilateral with unit edges in M_i scores exactly 1.
std::vector<double> leeQuality(const SurfaceMesh& mesh, const Metric3Field& m3);

/// Metric edge lengths of the surface mesh's unique edges: sqrt(eᵀ M_avg e) (eq. 3 in 3D).
std::vector<double> surfaceEdgeLengths(const SurfaceMesh& mesh, const Metric3Field& m3);

/// Every edge in ≤ 2 triangles and each interior edge used once in each direction (a
/// consistently oriented manifold with boundary). Returns an empty string or the first problem.
std::string checkManifold(const SurfaceMesh& mesh);

/// Edges that lie in one triangle only (0 for a closed surface).
long countBoundaryEdges(const SurfaceMesh& mesh);

}  // namespace ablmg::mesher
