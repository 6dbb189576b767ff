#pragma once
/// Size-gradient limiting of a per-vertex metric field ("hgrad" of MMG/BAMG), anisotropy kept.
///
/// Metric-space gradation (F. Alauzet, "Size gradation control of anisotropic meshes",
/// Finite Elem. Anal. Des. 46 (2010), §3): along an edge e = x_j − x_i, the metric M_i grown to
/// x_j is  η(e) M_i  with  η = (1 + |e|_{M_i} ln β)^(−2)  (β = hgrad > 1), i.e. the sizes of M_i
/// may grow by at most the factor (1 + |e|_{M_i} ln β) ≈ β^{|e|_{M_i}} over the edge. M_j is
/// replaced by M_j ∩ η M_i (core::intersect: the largest ellipse in both unit balls, so the
/// anisotropy of both is kept) whenever η M_i is not already contained in M_j. Sweeps over the
/// edges, alternately forward and backward in sorted edge order, both directions of each edge,
/// repeat until a sweep changes nothing (beyond a relative tolerance) or maxSweeps.
///
/// Guarantee on return (when converged): for every edge and direction, M_j ≥ (1 − tol)·η M_i
/// in the SPD order, so the sizes of M_j in any direction are at most (1 + |e|_{M_i} ln β)/√(1−tol)
/// times those of M_i. Metrics only grow (sizes only shrink). A field that already satisfies
/// the bound is returned bit-for-bit unchanged.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include <span>
#include <vector>

namespace ablmg::adapt {

struct GradationOptions {
  double hgrad = 1.5;       ///< β > 1: largest size growth factor per unit metric length
  double tolerance = 1e-3;  ///< relative slack before a metric is corrected (see above)
  int maxSweeps = 200;
};

struct GradationStats {
  int sweeps = 0;
  long corrections = 0;  ///< metrics replaced by an intersection, all sweeps
  bool converged = false;
};

/// In place. metrics.size() == mesh.numVertices(). Throws InputError for hgrad ≤ 1 or a size mismatch.
GradationStats limitGradation(const Mesh2& mesh, std::vector<Metric2>& metrics, const GradationOptions& options = {});

/// Largest eigenvalue of B^(−1) A (generalised): > 1 iff A is not contained in B, i.e. A asks
/// for a smaller size than B in some direction.
double maxGeneralisedEigenvalue(const Metric2& a, const Metric2& b);

}  // namespace ablmg::adapt
