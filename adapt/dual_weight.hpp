#pragma once
/// Dual-weighted density correction of the metric for the FE L2 error (AdaptOptions::dualWeight).
///
/// The FE L2 error is not the interpolation error the Hessian metric equidistributes: with z the
/// solution of the dual problem −∇·(κ∇z) = e (z = 0 where u is prescribed) and z_h its P1
/// Galerkin approximation, Galerkin orthogonality gives (Aubin–Nitsche; the dual-weighted
/// residual method of R. Becker, R. Rannacher, "An optimal control approach to a posteriori
/// error estimation in finite element methods", Acta Numerica 10 (2001) 1–102)
///
///   ‖e‖²_L2 = a(e, z − z_h) = Σ_T ∫_T κ ∇e·∇(z − z_h),
///
/// so the error is generated where ∇e and ∇(z − z_h) are both large, not where the local
/// interpolation error is. The per-triangle indicator here replaces both factors by
/// Zienkiewicz–Zhu gradient recovery (O. C. Zienkiewicz, J. Z. Zhu, Int. J. Numer. Methods
/// Eng. 24 (1987) 337–357: the vertex gradient G v = area-weighted mean of the gradients of
/// the triangles around it) and the unknown dual load e by 1 (z: −∇·(κ∇z) = 1, the same
/// Dirichlet boundaries with value 0, no Neumann flux): a dual that is smooth where the data
/// are and singular where the domain is (a reentrant corner), as the true one:
///
///   η_T = ‖G u_h − ∇u_h‖_T · ‖G z_h − ∇z_h‖_T   (‖·‖_T by the 3-vertex rule).
///
/// Equidistribution: at fixed N, Σ_T η_T with η_T ∝ w/d² per triangle (d the density, η ~ h⁴
/// for smooth u and z) is least when η_T is the same on every triangle, i.e. d ∝ √w; a density
/// step d ← d · (η_T/η̄)^γ with γ = ½ would reach it in one step on a fixed w. The loop uses a
/// damped γ (default ¼): the Hessian metric M_k (p = ∞, density √det|H| ∝ λ) is multiplied by
/// s = η^γ of the current mesh and rescaled to N; at a fixed point of the passes d = D λ ·
/// (w/d²)^γ, i.e. d ∝ λ^(1/(1+2γ)) w^(γ/(1+2γ)) = λ^(2/3) w^(1/6) for γ = ¼: p = 2's density
/// where the dual is smooth (w ∝ λ), p = ∞'s λ where it is as singular as u (w ∝ λ², corners).
/// The factor is clamped to [1/2, 2] (kMaxFactor): unclamped it spans 0.1–10 on some meshes, and
/// the line singularity's L2 error then stalls (rate over the last four sizes −0.79 → −0.28; −0.50
/// clamped), for little gain elsewhere (steep front 0.71 unclamped, 0.76 clamped).
///
/// Measured (examples/compare_freefem/run.sh --problem all --maxnv 4e4, worst ratios to FreeFem++
/// over the cycles ≥ 5·10³ vertices, L2 / H1, γ = 0 → ¼): steep front 1.29/0.37 → 0.76/0.38, wave
/// front 0.79/0.84 → 0.60/0.84, peak 0.66/0.92 → 0.52/0.91, multiple 0.61/0.86 → 0.44/0.86, the
/// corners within ±0.02, the layer 0.03/0.47 → 0.02/0.49, the line singularity 0.10/0.89 →
/// 0.16/0.87. The L2 rates over the last four sizes: steep front −0.68 → −0.82, layer −0.96 →
/// −0.63, line singularity −0.79 → −0.50 (their errors stay at 0.02–0.16× FreeFem's). Cost: one
/// more solve per cycle (the dual; same matrix, a new factorisation).
///
/// One step from the loop's 1.4·10⁴-vertex mesh of the wave front α = 1000 to 2.8·10⁴ vertices
/// (remeshed by the same mesher; errors of the new mesh; scripts/front_l2_dwr.py): L2 4.8·10⁻⁴
/// → 2.6·10⁻⁴ at H1 0.58 → 0.60 (the true dual and ∇e: 2.4·10⁻⁴, 0.63; γ = ½: 3.8·10⁻⁴, 0.89).
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/poisson_problem.hpp"
#include <span>
#include <vector>

namespace ablmg::adapt {

/// The dual problem above for `problem`: same κ (per subdomain too), f = 1, every Dirichlet
/// datum (per tag and the default) 0, no Neumann flux.
fem::PoissonProblem unitLoadDual(const fem::PoissonProblem& problem);

/// η_T above, per triangle of `mesh`; u and z per vertex (size numVertices()).
std::vector<double> dualWeightedIndicators(const Mesh2& mesh, std::span<const double> u, std::span<const double> z);

/// Largest factor (and 1/kMaxFactor the smallest) of dualWeightScale.
inline constexpr double kMaxFactor = 2.0;

/// Per-vertex density factor s_v = mean over the triangles at v of (η_T / η̄)^γ, η̄ the geometric
/// mean of the η_T (each floored at 10⁻¹² max η first), clamped to [1/kMaxFactor, kMaxFactor];
/// all ones when every η_T is 0. γ > 0.
std::vector<double> dualWeightScale(const Mesh2& mesh, std::span<const double> indicators, double gamma);

}  // namespace ablmg::adapt
