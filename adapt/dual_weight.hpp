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
///
/// Anisotropy (AdaptOptions::dualShare). On a triangle stretched along a direction where u is flat
/// (u_xx = 0, sizes h_x ≫ h_y, metric-equilateral), the interpolant of a dual curved along x has
/// the gradient error h_x²/(8 h_y) · z_xx across the triangle (P1 on the vertices (0, 0), (h_x, 0),
/// (h_x/2, h_y) of z = x²/2), so per unit area ∇(u − Πu)·∇(z − Πz) ≈ |u_yy| (h_y² |z_yy| +
/// h_x² |z_xx|): the L2 error is set by h_x where z is curved, however fine h_y. The density factor
/// above cannot fix it (it scales both sizes); the dual's own metric M(z; φ_z N), intersected with
/// u's, bounds h_x (the L2-goal metric of the term would be built on |u_yy|·|H_z|, M. Loseille,
/// A. Dervieux, F. Alauzet, J. Comput. Phys. 229 (2010) 2866–2897). Measured on the line
/// singularity (u = cos(πy/2) where s < 0: x-aligned triangles of aspect ≈ 50 there at 3·10⁴
/// vertices hold 99 % of the L2² error as a smooth bump 4× the interpolation error's size):
/// `--max-aniso 10` makes its FE L2 error its interpolation error (rate −1.06) but its H1 1.00×
/// FreeFem's. Worst ratios to FreeFem++ and L2 rate (run.sh's stored loops at 2–4·10⁴, means of seeds 1, 2)
/// for φ_z = 0 / 0.01 / 0.02 / 0.05: line singularity 0.22/0.87, −0.18 → 0.21/0.88, −0.13 →
/// 0.10/0.93, −0.84 → 0.08/1.00, −1.04; steep front 0.74/0.38, −0.84 → 0.68/0.39, −0.92 →
/// 0.71/0.39, −0.88 → 0.68/0.39, −0.9; tanh layer 0.02/0.49, −0.64 → 0.04/0.54, −0.63 →
/// 0.06/0.58, −0.66 → 0.11/0.66, −0.75 (its stretching is what its H1 needs: an anisotropy cap of
/// 3000 gives L2 0.16 and H1 0.87). 0.01 is the default: the line singularity's H1 bar (0.9) stops
/// it below 0.02; the other seven problems move by ≤ 0.05 (multiple's L2 0.50 → 0.45).
///
/// Goal weighting (AdaptOptions::dualGoal). The term above is |u_yy| h_x² |z_xx| per unit area:
/// the dual's curvature matters in proportion to u's second derivatives. Integrating the
/// error term by parts on each side, ∫ ∇(u − Πu)·∇(z − Πz) ≈ −∫ Δu (z − Πz) − ∫ Δz (u − Πu)
/// up to the element jumps, whose first part is the interpolation error of z weighted by |Δu|:
/// the metric of |Δu_h| |H_z| (Loseille–Dervieux–Alauzet's goal-oriented Hessian for this
/// functional; the second part, |Δz| |H_u| = |H_u| for the unit-load dual, is u's own metric).
/// With it, M(u; (1 − φ − φ_z) N) ∩ M(|Δu_h| |H_z|; φ_z N): the dual's share goes where u is
/// curved. Measured (`examples/compare_freefem/run.sh`'s FreeFem++ loop to 2.96·10⁴ vertices,
/// defaults otherwise; worst ratios L2 / H1, L2 rate over the last four sizes) on the line
/// singularity: off 0.15/0.87, −0.56; on with φ_z = 0.01 0.22/0.87, −0.65; 0.02 0.08/0.92,
/// −1.01; 0.03 0.06/0.95, −1.08 (the H1 bar 0.9 is crossed where the rate bar is met, as with
/// the unweighted share). On the tanh layer a goal share of 0.05–0.1 concentrates the whole
/// share in the layer (|Δu| ~ 10⁴ there) with sizes of aspect ≈ 1, and its L2 error rises 20×
/// (`ablmg adapt --problem tanhlayer --vertices 20000 --max-aniso 1e4`: 1.2·10⁻⁶ → 2.5–2.8·10⁻⁵).
/// Off by default.
///
/// H1 weighting (AdaptOptions::h1Weight). The same equidistribution for the H1 error: with ε_T =
/// ‖G u_h − ∇u_h‖_T (the Zienkiewicz–Zhu estimate of ‖∇(u − u_h)‖_T) and ε_T² ∝ w_u/d² per triangle,
/// Σ ε_T² at fixed N is least when ε_T is the same everywhere; d ← d (ε_T/ε̄)^γ₁ moves towards it
/// (γ₁ = 1 in one step on a fixed w). Where the Hessian model is right (a resolved feature, the
/// asymptotic regime) the mesh it builds already equidistributes ε and the factor is ≈ 1; it acts
/// where the model is wrong: a feature the current mesh has not resolved (the peak's core before
/// 10⁴ vertices), the recovered Hessian at a singular corner (a patch average). With ε_T ∝ √w_u/d
/// (w_u ∝ λ² for the H1 error, λ = √det|H|) a fixed point of the passes with the dual weight has
/// d^(1+2γ+γ₁) ∝ λ w^γ w_u^(γ₁/2): where the model holds (w_u ∝ λ², w ∝ λ for a smooth dual)
/// d ∝ λ^((1+γ+γ₁)/(1+2γ+γ₁)), so γ₁ pulls back towards p = ∞'s λ (the H1-optimal density)
/// where the dual weight pulls towards p = 2's (⅚ at (¼, 0), 0.92 at (⅛, ¼)).
/// Measured (`ablmg adapt` at examples/compare_freefem/run.sh's sizes to 0.6–1.1·10⁵ vertices, worst
/// H1 ratio to FreeFem++ over the cycles ≥ 5·10³ vertices; docs/experiments.md has the whole
/// table): at hgrad 1.5, (γ, γ₁) = (¼, 0) → (⅛, ¼): the L-shape 0.893 → 0.885, 5π/4 0.892 → 0.885,
/// 7π/4 0.890 → 0.883, the slit 0.898 → 0.893, the peak 0.881 → 0.877, multiple 0.844 → 0.811, the
/// layer 0.51 → 0.41; the steep front's L2 0.57 → 0.79 (what γ is for; its H1 0.81 → 0.78). z's
/// factor alone costs the corners H1 (the L-shape at 7.6·10³ vertices, hgrad 1.25: 0.893 with (¼, 0), 0.882
/// with u's factor only, (0, ¼)); γ₁ = ½ or ¾ gains nothing more (the slit 0.897 / 0.899).
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

/// ε_T = ‖G u_h − ∇u_h‖_T per triangle (G as above): the Zienkiewicz–Zhu estimate of the local
/// H1 error of u_h, the indicator of AdaptOptions::h1Weight ("H1 weighting" above).
std::vector<double> recoveryErrorIndicators(const Mesh2& mesh, std::span<const double> u);

/// The loop's density factor for dualWeight γ and h1Weight γ₁ (both ≥ 0, not both 0): s_v = mean
/// over the triangles at v of (η_T/η̄)^γ (ε_T/ε̄)^γ₁ = (ε_T/ε̄)^(γ+γ₁) (ε^z_T/ε̄^z)^γ (geometric
/// means, as dualWeightScale), clamped to [1/kMaxFactor, kMaxFactor]; z is read only when γ > 0.
std::vector<double> densityWeightScale(const Mesh2& mesh, std::span<const double> u, std::span<const double> z,
                                       double dualGamma, double h1Gamma);

/// Largest factor (and 1/kMaxFactor the smallest) of dualWeightScale.
inline constexpr double kMaxFactor = 2.0;

/// Per-vertex density factor s_v = mean over the triangles at v of (η_T / η̄)^γ, η̄ the geometric
/// mean of the η_T (each floored at 10⁻¹² max η first), clamped to [1/kMaxFactor, kMaxFactor];
/// all ones when every η_T is 0. γ > 0.
std::vector<double> dualWeightScale(const Mesh2& mesh, std::span<const double> indicators, double gamma);

}  // namespace ablmg::adapt
