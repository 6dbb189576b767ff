#pragma once
/// From recovered Hessians to the anisotropic metric of a target complexity that is optimal
/// for the interpolation error e = u − Π_h u of P1 elements in 2D, measured in one of two
/// norms (MetricOptions::norm). |H| = R diag(λ1, λ2) Rᵀ (absolute eigenvalues), det|H| = λ1 λ2.
///
/// L2 (default): the Lp norm of e. Continuous-mesh framework (A. Loseille, F. Alauzet,
/// "Continuous mesh framework part I/II", SIAM J. Numer. Anal. 49 (2011)):
///
///   M_p(x) = D · det|H(x)|^(−1/(2p+2)) · |H(x)|,    D = C / ∫_Ω det|H|^(p/(2p+2)) dx,
///
/// p ∈ [1, ∞) (p = ∞: M = D |H|, D = C / ∫ √det|H|).
///
/// H1: the W^{1,p} seminorm of e (p = 2: the H1 seminorm),
///
///   M_{1,p}(x) = D · det|H|^(p/(p+2)) · |H|² / det|H|,   D = C / ∫_Ω det|H|^(p/(p+2)) dx,
///
/// p = 2: M = D |H|² / √det|H|;  p = ∞: M = D |H|². Derivation (local analysis, the usual
/// first-order model): on an element of sizes h1, h2 along the eigenvectors of |H| (metric
/// eigenvalues μ_i = h_i^(−2), density d = √det M = 1/(h1 h2)), |∇e|² ≈ c (λ1² h1² + λ2² h2²)
/// = c (λ1²/μ1 + λ2²/μ2). At fixed d write μ1 = d r, μ2 = d / r: c (λ1²/r + λ2² r)/d is least
/// at r = λ1/λ2, i.e. μ1/μ2 = (λ1/λ2)², the shape |H|²/det|H| (aspect ratio h2/h1 = λ1/λ2,
/// the square of the Lp shape's √(λ1/λ2)), and there |∇e|² ≈ 2c det|H| / d. Minimising
/// ∫ (det|H|/d)^(p/2) dx at fixed ∫ d dx = C (Lagrange: (p/2) det|H|^(p/2) d^(−p/2−1) = const)
/// gives d ∝ det|H|^(p/(p+2)); M = d · |H|²/det|H| (det of the shape = 1).
///
/// Caveat (why H1 is not the default): the model above keeps only the first term of the exact
/// gradient error of the interpolant of q = ½ xᵀHx on a triangle that is equilateral in M
/// (edge 1 and circumradius ρ = 1/√3 in metric units; checked against direct integration):
///
///   ∫_T |∇(q − Π q)|² = |T| ρ² [ (λ1² h1² + λ2² h2²)/8 + (a − b)²/16 · (cos²ψ/h1² + sin²ψ/h2²) ],
///
/// a = λ1 h1², b = ±λ2 h2² (the sign of det H), ψ = 3 × the angle, in metric space, from e1 to
/// a vertex seen from the centroid. The second term (the interpolant's gradient error at the
/// centroid) vanishes for the Lp shape (a = b) where H is definite and is small for any shape
/// only when a triangle has an edge along e1 (ψ = π/2: acute needles across the steep
/// direction). With a lattice oriented by the global axes ψ is arbitrary and the H1 shape pays
/// (a − b)² ≈ λ1⁴ h1⁴/λ2²: on Mitchell's wave front (α = 20) `norm H1` (p = 2) had about twice
/// the H1 error of the L2 metric (p = 4) at equal N, and overshoots N at 10⁵ vertices
/// (anisotropy ratios are squared). The adaptive loop therefore starts the bubble lattice with
/// a row along each node's short-size direction (mesher::LatticeOrientation::ShortAxis), and
/// then shapeBlend 0.25 pays: H1 0.82–0.91×, L2 0.62–0.74× FreeFem's on the wave front (docs/method.md).
///
/// shapeBlend w (optional) replaces the norm's own shape by (|H|/√det|H|)^(1+w), unit
/// determinant: w = 0 the Lp shape, w = 1 the H1 shape, w = ½ their log-Euclidean (geometric)
/// mean; the density d keeps the norm's exponent. So `norm L2, shapeBlend w` = Lp density with a
/// shape leaning towards H1; M = D · det|H|^δ · (|H|/√det|H|)^(1+w), δ = p/(2p+2) (L2) or
/// p/(p+2) (H1).
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
/// Far-field floor (hmaxUniform κ, off by default): h ≤ κ h_N, h_N = √(2|Ω|/(√3 N)) the size of
/// the uniform unit mesh of N vertices. Why one might want it: the FE L2 error is not the
/// interpolation error the metric equidistributes. By duality (Aubin–Nitsche; e.g. S. C. Brenner,
/// L. R. Scott, "The mathematical theory of finite element methods", 3rd ed., Springer 2008,
/// §5.4), with z the solution of −Δz = e (z = 0 where u is prescribed) and z_h its P1 Galerkin
/// approximation, ‖e‖²_L2 = a(e, z − z_h) = Σ_T ∫_T ∇e·∇(z − z_h), and
/// ‖∇(z − Π z)‖_T ≲ h_T |z|_H2(T) with h_T the element's largest size. Where the dual is smooth
/// (a convex domain, no singular data) the bound is ‖e‖_L2 ≲ ‖∇e‖ · max_T h_T: a mesh that is
/// H1-optimal (‖∇e‖ ~ N^(−1/2)) gets the L2 rate N^(−1) only if its largest elements shrink like
/// N^(−1/2), which h ≤ κ h_N ensures at a cost of at most 1/κ² of the vertices. Measured on the
/// wave front of α = 1000 (examples/compare_freefem/run.sh's FreeFem++ loop to 2.8·10⁴
/// vertices, the loop's defaults otherwise): the L2 ratio to FreeFem's at 2.8·10⁴ vertices
/// 1.29 → 1.06 / 1.12 / 1.06 at κ = 2 / 3 / 5, but the peak's H1 ratio 0.92 → 1.04 at κ = 2. The
/// steep front's L2 error is generated beside the front, not in the far field (adaptive_loop.hpp,
/// l2Share), so the floor buys little there; hence off.
///
/// Integrals over Ω are computed on the given mesh: per triangle, area × mean of the three
/// vertex values.
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ablmg::adapt {

/// The norm of the interpolation error the metric is optimal for (see above).
enum class ErrorNorm {
  L2,  ///< Lp norm of e: M_p (default)
  H1,  ///< W^{1,p} seminorm of e: M_{1,p}
};

/// "l2" / "h1" ↔ ErrorNorm; parse throws InputError naming the valid names.
ErrorNorm parseErrorNorm(const std::string& name);
std::string toString(ErrorNorm norm);

struct MetricOptions {
  double targetVertices = 1e4;       ///< N (> 0); the complexity aimed at is (√3/2) N
  double p = 2;                      ///< the exponent p of the norm (Lp or W^{1,p}), ≥ 1 or infinity()
  ErrorNorm norm = ErrorNorm::L2;    ///< which error the metric is optimal for
  std::optional<double> shapeBlend;  ///< w ∈ [0, 1]: shape (|H|/√det|H|)^(1+w); empty = the norm's own (L2: 0, H1: 1)
  /// σ ∈ [0, 1] (0: off): on indefinite Hessians the shape S becomes S^½ C S^½ (det kept),
  /// C of aspect 3^(σw/2) with its long axis at 45° to H's eigenvectors, w = the saddle weight,
  /// 0 for −r ≤ 0.55 rising linearly to 1 at −r = 0.65, r = −(smaller |λ|)/(larger |λ|) (−1 on
  /// a harmonic saddle). Why: for a saddle q = ½(x² − y²) the P1 triangle of least H1
  /// interpolation error per area is right isosceles with its legs along the eigenvectors,
  /// 0.866× an equilateral triangle's H1² (Mirebeau's shape analysis for W^{1,p}, Numer. Math.
  /// 2012; scripts/saddle_triangle_shape.py); it is the metric-equilateral triangle of C at
  /// σ = 1 whose base runs along C's long axis, and costs +4.5 % at 5° misorientation, +44 % at
  /// 30°. The mesher builds that triangle from the lattice rows of saddleLatticeRows (below),
  /// carried per vertex by the background field. For H = diag(1, −β) and the loop's shape
  /// (exponent 1.05) the corrected triangle beats the plain one (rows along the short axis) for
  /// β ≥ 0.6 (β = 0.7: −5 %, 0.8: −8 %, 1: −13 % H1²) and loses below (β = 0.5: +4 %, 0.25: +24 %),
  /// hence the weight's narrow ramp at 0.6. Measured against FreeFem++ (examples/compare_freefem,
  /// `--maxnv 4e4`, worst ratios over the cycles ≥ 5·10³, L2 / H1), σ = 0 → 1: L-shape
  /// 0.86/0.96 → 0.75/0.91, 5π/4 0.83/0.96 → 0.76/0.91, 7π/4 0.86/0.96 → 0.75/0.91, slit
  /// 0.93/0.97 → 0.82/0.91, peak 0.52/0.91 → 0.51/0.90; the others within ±0.03. Default 0 here,
  /// 1 in the adaptive loop (AdaptOptions::metric).
  double saddleShape = 0;
  double hmin = 0;                                        ///< smallest size (coordinate units), ≥ 0
  double hmax = std::numeric_limits<double>::infinity();  ///< largest size, > hmin
  double maxAnisotropy = 1e4;                             ///< largest h1/h2 (≥ 1)
  /// κ (> 0): largest size as a multiple of the uniform size for N vertices, h ≤ κ h_N with
  /// h_N = √(2|Ω|/(√3 N)) (the far-field floor above); ∞ (default) = none.
  double hmaxUniform = std::numeric_limits<double>::infinity();
  double eigenFloor = 1e-10;  ///< relative floor on |λ(H)| (> 0)
};

/// The saddle correction of MetricOptions::saddleShape applied to the shape `s` of Hessian `h`
/// (unchanged where h is not indefinite); det S^½ C S^½ = det S. C's long axis lies at +45° to
/// H's positive eigenvector, or at −45° when `wall` (a unit boundary tangent, 0 off the
/// boundary) is closer to the normal of the +45° axis than to the axis itself. Why: both sides
/// give the same right isosceles triangle (mirror images), but next to a wall the mesh's first
/// row has its base along the wall, and boundary nodes are spaced by the metric's length along
/// the wall: with the long axis normal to it they were √3 too close and the first rows carried
/// 1.4–1.7× an equilateral triangle's H1² (L-shape, wall x = 0, 7.9·10³ vertices;
/// scripts/triangle_shape_efficiency.py). Flipping the side at boundary vertices only (interior
/// vertices keep +45°: a flipped region's seam costs what the wall gains) took that wall to
/// 1.0–1.06 and the L-shape's H1 ratio to FreeFem++ 0.908 → 0.901 at 7.9·10³ vertices.
Hessian2 saddleShaped(const Hessian2& h, const Hessian2& s, double sigma, const Vec2& wall = Vec2::Zero());

/// Per-vertex lattice rows for the saddle shape (MetricField::latticeRow; all zero when
/// options.saddleShape = 0): where H is indefinite, w (cos 2α, sin 2α) with w the saddle weight
/// above and t = (cos α, sin α) ∝ S^(−1/2) c1, c1 the long axis of C and S the
/// norm's shape (eigenvalues |λ|^(1+shapeBlend) up to a factor: S^(−1/2) c1 ∝
/// e₊ |λ₊|^(−(1+w')/2) + e⊥ |λ₋|^(−(1+w')/2), e₊ the eigenvector of the positive eigenvalue,
/// e⊥ = e₊ turned by +90°). Why: M = S^½ C S^½ maps x to y = S^½ x, where C's metric-equilateral
/// triangle with an edge along c1 is the right isosceles one; a lattice row along t is that
/// edge in the plane (on a harmonic saddle S ∝ I and t is M's long axis, the long-axis lattice).
/// Elsewhere 0: the mesher keeps its own orientation there. `walls` (empty, or one unit tangent
/// per vertex, wallTangents) picks the side as saddleShaped does.
std::vector<Vec2> saddleLatticeRows(std::span<const Hessian2> hessians, const MetricOptions& options,
                                    std::span<const Vec2> walls = {});

/// Unit tangent of the boundary at each boundary vertex of `mesh` (0 at interior vertices and at
/// corners, where the boundary turns by more than 20°).
std::vector<Vec2> wallTangents(const Mesh2& mesh);

/// Singular grading at the reentrant corners of the boundary (vertices where it turns by more than
/// 20° with an interior angle > π, a slit's tip included; convex corners are left alone).
/// Fits h = A r^σ to the metric's sizes h = det(M)^(−1/4) at the vertices of rings 3–6 around
/// the corner (r: their distance to it; the inner rings' recovered Hessians are averages over
/// patches that reach the corner). Where σ ∈ (0.2, 0.95), i.e. |H| grows towards the corner
/// like r^(−2σ) (u ~ r^a: σ = 1 − a/2 for M ∝ |H|, p = ∞), the graded mesh h(r) = A r^σ ends at
/// the ring where h = r, r* = A^(1/(1−σ)), and the corner's metric is intersected with the
/// isotropic one of size max(β r*, hc/4, hmin), hc its own size (hc/4: at most a quarter per
/// remesh, so that a coarse mesh, whose complexity integral cannot see the corner, is not
/// starved). Convex corners are excluded because the fit is not enough: on the line singularity
/// (u = cos(πy/2) + ..., |H| → 0 on y = ±1) three of the square's corners fitted σ = 0.2–0.5,
/// were refined 4× each pass, and its L2 error rose once with N. Why: the
/// triangles at a reentrant corner carry the singular part of the error, which the Hessian
/// model does not see: with the corner's own size (≈ r*) the L-shape's 7 triangles within 10⁻⁴
/// of the corner held 1.7 % of the H1² error at 7.9·10³ vertices, 38× the mean triangle's
/// (scripts/corner_h1_bands.py); the element error there scales like ρ^(2a), so β = ¼ lowers it
/// 6× (a = ⅔) for a few dozen vertices. Returns the number of corners changed; throws
/// InputError unless β ∈ (0, 1] and metric.size() == mesh.numVertices().
int gradeSingularCorners(const Mesh2& mesh, std::vector<Metric2>& metric, double beta, double hmin);

/// Throws InputError naming the option and value if out of range.
void validate(const MetricOptions& options);

/// |H| = R |Λ| Rᵀ with each |λ| ≥ floor (absolute).
Hessian2 absoluteHessian(const Hessian2& h, double floor);

/// M_p (norm L2) or M_{1,p} (norm H1) as above, per vertex of `mesh`. hessians.size() == mesh.numVertices().
std::vector<Metric2> metricFromHessians(const Mesh2& mesh, std::span<const Hessian2> hessians,
                                        const MetricOptions& options);

/// C = ∫_Ω √det M dx on `mesh` (per-vertex metrics).
double metricComplexity(const Mesh2& mesh, std::span<const Metric2> metrics);

/// (√3/2) N: the complexity whose unit mesh has ≈ N vertices.
double complexityForVertices(double vertices);

/// min(hmax, κ h_N) of the far-field floor (κ = options.hmaxUniform, |Ω| the mesh's area).
double effectiveHmax(const Mesh2& mesh, const MetricOptions& options);

/// Applies hmin, hmax and maxAnisotropy to one metric (eigenvectors unchanged).
Metric2 boundMetric(const Metric2& m, double hmin, double hmax, double maxAnisotropy);

/// Vertex-wise intersection of two metric fields on the same vertices (core::intersect).
std::vector<Metric2> intersectFields(std::span<const Metric2> a, std::span<const Metric2> b);

}  // namespace ablmg::adapt
