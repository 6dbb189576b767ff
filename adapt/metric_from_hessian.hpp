#pragma once
/// From recovered Hessians to the Lp-optimal anisotropic metric of a target complexity.
///
/// Continuous-mesh framework (A. Loseille, F. Alauzet, "Continuous mesh framework part I/II",
/// SIAM J. Numer. Anal. 49 (2011)): for P1 interpolation in 2D the metric minimising the
/// Lp norm of the interpolation error at complexity C = ∫_Ω √det M dx is
///
///   M_p(x) = D · det|H(x)|^(−1/(2p+2)) · |H(x)|,    D = C / ∫_Ω det|H|^(p/(2p+2)) dx,
///
/// p ∈ [1, ∞) (p = ∞: M = D |H|, D = C / ∫ √det|H|), |H| = R |Λ| Rᵀ (absolute eigenvalues).
///
/// Complexity ↔ vertices: a unit-metric mesh of equilateral triangles has triangle area √3/4
/// in metric space, ≈ 2 triangles per vertex, so N_vertices ≈ (2/√3) C — the same estimate
/// the mesher uses (PlacementStats::predictedNodes). We therefore aim at C = (√3/2) N for a
/// target of N vertices (boundary vertices add a few percent on coarse meshes).
///
/// Bounds (applied to the sizes h = λ^(−1/2) after scaling): h ∈ [hmin, hmax] and the
/// anisotropy ratio h_max/h_min ≤ maxAnisotropy (the smaller size is raised). Because the
/// bounds change ∫√det M, D is re-adjusted by a fixed-point iteration until the bounded
/// metric has the requested complexity (relative tolerance 1e-3, or the bounds make it
/// unreachable: then the closest value). Tiny eigenvalues (|λ| < eigenFloor · max|λ| over
/// the mesh, e.g. where u is linear) are raised to that floor before the scaling.
///
/// Integrals over Ω are computed on the given mesh: per triangle, area × mean of the three
/// vertex values.
#include "adapt/hessian_recovery.hpp"
#include "core/mesh2.hpp"
#include "core/metric2.hpp"
#include <limits>
#include <span>
#include <vector>

namespace ablmg::adapt {

struct MetricOptions {
  double targetVertices = 1e4;  ///< N (> 0); the complexity aimed at is (√3/2) N
  double p = 2;                 ///< Lp norm of the interpolation error, ≥ 1 or infinity()
  double hmin = 0;              ///< smallest size (coordinate units), ≥ 0
  double hmax = std::numeric_limits<double>::infinity();  ///< largest size, > hmin
  double maxAnisotropy = 1e4;   ///< largest h1/h2 (≥ 1)
  double eigenFloor = 1e-10;    ///< relative floor on |λ(H)| (> 0)
};

/// Throws InputError naming the option and value if out of range.
void validate(const MetricOptions& options);

/// |H| = R |Λ| Rᵀ with each |λ| ≥ floor (absolute).
Hessian2 absoluteHessian(const Hessian2& h, double floor);

/// M_p as above, per vertex of `mesh`. hessians.size() == mesh.numVertices().
std::vector<Metric2> metricFromHessians(const Mesh2& mesh, std::span<const Hessian2> hessians, const MetricOptions& options);

/// C = ∫_Ω √det M dx on `mesh` (per-vertex metrics).
double metricComplexity(const Mesh2& mesh, std::span<const Metric2> metrics);

/// (√3/2) N: the complexity whose unit mesh has ≈ N vertices.
double complexityForVertices(double vertices);

/// Applies hmin, hmax and maxAnisotropy to one metric (eigenvectors unchanged).
Metric2 boundMetric(const Metric2& m, double hmin, double hmax, double maxAnisotropy);

/// Vertex-wise intersection of two metric fields on the same vertices (core::intersect).
std::vector<Metric2> intersectFields(std::span<const Metric2> a, std::span<const Metric2> b);

} // namespace ablmg::adapt
