#pragma once
/// A-posteriori estimate of the P1 interpolation error ‖u − I_h u‖_L2 from recovered Hessians:
/// the error measure of the loop when the exact solution is unknown (adaptive_loop.hpp), and the
/// quantity the Lp metrics of metric_from_hessian.hpp minimise.
///
/// For a quadratic u with Hessian H, the error on a triangle T with vertices x_0, x_1, x_2 and
/// barycentric coordinates λ_i is, exactly,
///     u − I_h u = −½ Σ_{i<j} λ_i λ_j a_ij,    a_ij = (x_j − x_i)ᵀ H (x_j − x_i)
/// (a quadratic vanishing at the vertices, −a_ij/8 at the edge midpoints), so
///     ‖u − I_h u‖²_{L2(T)} = ¼ Σ_{i<j} Σ_{k<l} a_ij a_kl ∫_T λ_i λ_j λ_k λ_l,
///     ∫_T λ_0^p λ_1^q λ_2^r = 2|T| p! q! r! / (p + q + r + 2)!.
/// With H_T = the mean of the three vertex Hessians (signed, not |H|) this is exact whenever u
/// is quadratic on T and the recovery reproduces its Hessian (both recovery methods do,
/// hessian_recovery.hpp); for smooth u it estimates l2Interp of fem/error_norms.hpp.
/// Units: those of u times length.
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/core/mesh2.hpp"

#include <span>
#include <vector>

namespace ablmg::adapt {

struct InterpolationErrorEstimate {
  double l2 = 0;                  ///< sqrt(Σ_T elementL2²)
  std::vector<double> elementL2;  ///< per triangle
};

/// `hessians`: one per vertex of `mesh` (recoverHessians). Throws ablmg::Error on a size mismatch.
InterpolationErrorEstimate estimateInterpolationError(const Mesh2& mesh, std::span<const Hessian2> hessians);

}  // namespace ablmg::adapt
