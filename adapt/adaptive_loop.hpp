#pragma once
/// The adaptive solve loop: solve → errors → recover → metric → remesh, per cycle.
///
///   cycle k:  mesh_k ─ fem::solvePoisson ─▶ u_k ─ errors vs exact u ─▶ CycleReport
///             u_k ─ recoverHessians ─▶ H_k ─ metricFromHessians(N_{k+1}) [─ limitGradation]
///                 ─▶ M_k (per vertex of mesh_k) ─ mesher::meshDomain(domain, BackgroundMetricField(mesh_k, M_k))
///                 ─▶ mesh_{k+1}
///
/// mesh_0 is meshDomain with the uniform isotropic metric whose complexity is N_0 vertices
/// (size h = sqrt(2|Ω| / (√3 N_0)), see metric_from_hessian.hpp for the complexity ↔ vertex
/// relation). N_k = targetVertices[min(k, size − 1)]: an increasing list traces a convergence
/// curve, a single value iterates at fixed complexity.
///
/// Two ways to drive it:
///  - runAdaptiveLoop(problem, options, onCycle): everything above; onCycle sees each cycle's
///    mesh, solution, errors and metrics (for output: the library never prints or writes files).
///  - the steps on their own, for a solver with its own u_h: uniformMesh(), adaptMetric()
///    (mesh + u_h → per-vertex metric), remesh() (mesh + metric → new mesh, adapt/remesh.hpp).
///
/// hmax = ∞ in options.metric means a quarter of the current mesh's bounding-box diagonal (so
/// that regions where u is linear still get a few elements across the domain).
///
/// Row k of the report: vertices/triangles/errors/quality of mesh_k; t_mesh = time to build
/// mesh_k, t_solve = assembly + solve on it (split into t_assembly, t_ordering, t_factor =
/// CHOLMOD's analysis + factorisation + triangular solves), t_errors = the error norms against
/// the exact solution (not part of t_solve), t_recover/t_metric = building M_k from u_k (0 in
/// the last cycle, where no next mesh is built). Times are wall seconds (steady clock), the
/// only non-deterministic numbers in the report.
#include "ablmg/adapt/gradation.hpp"
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/adapt/interpolation_error.hpp"
#include "ablmg/adapt/metric_from_hessian.hpp"
#include "ablmg/adapt/remesh.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/material_problems.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/test_problems.hpp"
#include "ablmg/mesher/mesher.hpp"
#include <functional>
#include <optional>
#include <vector>

namespace ablmg::adapt {

/// The default schedule of `ablmg adapt --vertices N`: from a coarse start to N, sizes growing
/// geometrically, several adaptation passes at each size up to passesUpTo vertices. The coarse
/// passes are cheap (the cost of a cycle is about linear in N, so all cycles below N cost about
/// growth/(growth − 1) × the last one) and let the metric find thin features (a front of width
/// 1/1000, a peak, a corner) before the vertices are spent: a uniform mesh of N_0 vertices cannot
/// see a feature narrower than its size, the first adapted mesh sees it roughly, the second pass
/// at the same N resolves it. Measured (p = ∞, hgrad 1.3, to 2·10⁴ vertices, ratios to FreeFem++'s
/// adaptmesh loop at the same N): with one pass per size the wave front of α = 1000 had 33× and
/// the layer's H1 error 5.8× FreeFem's at 5·10³ vertices, with two passes 0.16× and 2.0×; at
/// 2·10⁴ the front's H1 ratio goes 0.49 → 0.39. The passes below 10⁴ add about a quarter of
/// the vertex-cycles of a run to 2·10⁴ (Σ N_k: 4·10⁴ → 5·10⁴). A third pass below 10⁴ (the
/// default, with the metric below; run.sh --maxnv 4e4, worst ratios over the cycles ≥ 5·10³
/// vertices, L2 / H1, shape blend 0.05, hgrad 1.3, 2 → 3 passes) takes the layer's H1 from 0.56 to 0.47 and the 7π/4 corner from
/// 0.94/1.00 to 0.87/0.97, other problems within ±0.04 except the steep front's L2 (1.33 → 1.46,
/// the mesh-to-mesh scatter of that problem is about ±0.1); it adds Σ N_k of about 1.5·10⁴ to a
/// run (a run to 3·10⁴ vertices: 7.4·10⁴ → 8.9·10⁴).
struct ScheduleOptions {
  double startVertices = 400;  ///< N_0 (≥ 10): the first size is in [N_0, growth · N_0), or N if N ≤ N_0
  double growth = 2;           ///< N_{k+1} / N_k (> 1); the last size is N exactly
  int passes = 3;              ///< adaptation passes per size (≥ 1) below passesUpTo
  double passesUpTo = 1e4;     ///< sizes ≥ this get one pass
};

/// Targets N_k of the schedule ending at `finalVertices` (≥ 10): N_0, ..., N each repeated
/// `passes` times while below passesUpTo; increasing, ends with finalVertices. Throws InputError
/// naming the field for values out of range.
std::vector<double> geometricSchedule(double finalVertices, const ScheduleOptions& options = {});

struct AdaptOptions {
  std::vector<double> targetVertices{1000, 2000, 4000, 8000};  ///< N_k (> 0 each; geometricSchedule builds one)
  int cycles = 0;                                              ///< 0 = targetVertices.size(); more repeats the last N
  HessianMethod hessian = HessianMethod::LeastSquares;
  /// p, norm, shapeBlend, hmin, hmax (∞: see above), anisotropy; targetVertices set per cycle.
  ///
  /// The loop's default is p = ∞ (norm L2: M = D |H|, density √det|H|), chosen across the whole
  /// problem library (docs/benchmarks.md, "Adaptive loop against FreeFem++"). Why not p = 2: the
  /// loop is judged on the finite-element errors, and near a singular point the FE L2 error is
  /// governed by the H1 grading (the dual problem is singular there too; Aubin–Nitsche). For
  /// u ~ r^λ, |H| ~ r^(λ−2): the density √det|H| ~ r^(λ−2) is the H1-optimal grading h ~ r^(1−λ/2)
  /// (equidistributing h⁴ r^(2λ−4) at fixed ∫ h⁻² dx), whereas p = 2's det|H|^(1/3) ~ r^(−2(2−λ)/3)
  /// is only L2-optimal for the interpolant. On the reentrant corner (λ = 2/3) p = 2 left both FE
  /// errors 1.4–2.5× those of FreeFem++'s adaptmesh (whose BAMG metric is this L∞ one) at
  /// 5·10³–2·10⁴ vertices; p = ∞ brings them to 0.83–0.98×. Where u is smooth (wave front, peak)
  /// p = ∞ costs little L2 and gains H1 (the W^{1,2}-optimal density, metric_from_hessian.hpp, is
  /// det|H|^(1/2) too).
  ///
  /// shapeBlend 0.05 (metric_from_hessian.hpp: the shape (|H|/√det|H|)^1.05, a little more
  /// anisotropic than the Lp one, towards the H1-optimal |H|²/det|H|; the density stays
  /// √det|H|). The blend trades L2 for H1 wherever the metric is anisotropic. Measured with
  /// examples/compare_freefem/run.sh --maxnv 4e4 (N ≈ 2–4·10⁴), worst ratios to FreeFem++ over
  /// the cycles ≥ 5·10³ vertices, L2 / H1, 2 passes per size, hgrad 1.3, shape blend 0.15 → 0.05:
  /// steep front (α = 1000) 2.06/0.36 → 1.33/0.37, multiple 0.81/0.82 → 0.63/0.85, line
  /// singularity 0.14/0.82 → 0.09/0.87, tanh layer 0.03/0.52 → 0.06/0.56 (0.47 with the third
  /// pass above), wave front 0.82/0.82 → 0.77/0.84, peak and corners within ±0.02; the L2 rates
  /// over the last four sizes rise to −1.10 (steep front; from −0.51), −0.80 (line singularity;
  /// −0.41). Blend 0 lets the layer's H1 error rise past FreeFem's (0.74 at 0; 0.84 at 0.05 with
  /// 2·10⁴ vertices, 2 passes). A blend only where H is definite (none on saddles and layers)
  /// keeps the steep front at 1.06 but puts the layer at 1.21: the layer needs it. With norm H1
  /// set, reset it for the norm's own shape (`ablmg adapt --norm h1` does).
  ///
  /// saddleShape 1 (metric_from_hessian.hpp: right isosceles triangles on near-harmonic saddles,
  /// built by the mesher from the per-vertex lattice rows the loop hands over with the metric):
  /// the corners' H1 0.96 → 0.91× FreeFem's, their L2 0.83–0.93 → 0.75–0.82×, the others within
  /// ±0.03 (measurements there).
  ///
  /// maxAnisotropy 10⁵ (MetricOptions' own default is 10⁴). Where u varies in one direction only
  /// (a straight layer: u_xx = 0) the Hessian sets no long size, and the cap is what sets it: at
  /// 10⁴ the layer's triangles were 0.1 × 10⁻⁵, and its FE L2 error stalled at 30–100× the
  /// interpolation error, a smooth error exported into the flat region beside the layer (77 % of
  /// L2² at distance ≥ 0.04 from it, 1.4·10⁴ vertices): the layer's L2 rate over the last four
  /// sizes −0.53 (to 3.6·10⁴ vertices) and −0.38 (to 9.5·10⁴). At 10⁵ the long size reaches hmax
  /// (the layer is meshed as rows across the domain, like the 1-d problem it is): −1.10 and
  /// −1.02, the final L2 error 6.8× and the H1 error 2.4× lower at 10⁵ vertices, the worst H1
  /// ratio to FreeFem++ 0.54 → 0.46. No other problem of the library reaches the cap (their
  /// errors are unchanged to the last digit; `examples/compare_freefem/run.sh --problem all
  /// --maxnv 4e4`). Capping the long size instead (hmax 0.05 or the far-field floor hmaxUniform)
  /// raises the layer's L2 error 10–40×. Cost: the sides crossing the layer carry one vertex per
  /// row of its triangles, so its meshes have 8–11 % more vertices (+1–2 % triangles; the
  /// complexity does not count boundary vertices) and its loop +9 % CPU (docs/experiments.md).
  MetricOptions metric = [] {
    MetricOptions m;
    m.p = std::numeric_limits<double>::infinity();
    m.shapeBlend = 0.05;
    m.saddleShape = 1;
    m.maxAnisotropy = 1e5;
    return m;
  }();
  /// > 1: gradation (gradation.hpp); ≤ 0: off. Default 1.25: without it the metric of a
  /// peak or of a layer falls from its refined core to hmax within one or two background
  /// elements, the mesher's transition elements there are poor (q < 0.5) and carry most of the
  /// error, and the peak's L2 error jumped by 2–7× between cycles (p = ∞, 5·10³–2·10⁴ vertices);
  /// with it the errors fall every cycle. The complexity is restored after grading (uniform
  /// rescale). Stronger gradation lowers the FE L2 error of the steep front, whose excess over
  /// the interpolation error lies in the transition bands beside the front (68 % of L2² at
  /// distances 3·10⁻³–0.1 from it, 1.4·10⁴ vertices), and costs H1 on the peak (run.sh, shape
  /// blend 0.05, 3 passes, hgrad 1.3 → 1.25 at 4·10⁴: steep front L2 1.46 → 1.20, peak H1 0.91 →
  /// 0.91, multiple 0.63/0.84 → 0.60/0.86; at 2·10⁴: hgrad 1.2 peak H1 0.92–0.93, 1.1: the steep
  /// front's L2 0.74–1.02 but the peak's H1 1.03 and the line singularity's 0.95–1.00). Default
  /// 1.5 since the dual weight carries the steep front's L2 (below): to 10⁵ vertices (run.sh's
  /// FreeFem++ loops, worst ratios over the cycles ≥ 5·10³, dual weight ¼, no H1 weight), 1.25 →
  /// 1.5: the peak's H1 0.900 → 0.881 (its 8.8·10³-vertex cycles, where the peak's core is not yet
  /// resolved and the transition rings around it are a larger share of the vertices), the layer
  /// 0.57 → 0.51, the line singularity 0.88 → 0.83, multiple 0.87 → 0.84, the corners ±0.002, the
  /// wave front 0.844 → 0.848, the steep front's L2 0.49 → 0.57; q mean ≥ 0.963 (0.971 before).
  double hgrad = 1.5;
  /// φ ∈ [0, 1): share of the complexity given to the L2-optimal metric M_2 (p = 2, same shape
  /// blend and bounds): the metric is M_p(u; (1 − φ) N) ∩ M_2(u; φ N) (core::intersect), rescaled
  /// to N (after gradation). Each part alone would cost at most a factor (1 − φ)^(−1/2) resp.
  /// φ^(−1/2) in its own norm's interpolation error; the intersection is a compromise between
  /// p = ∞'s H1-optimal grading and p = 2's L2-optimal one. 0 (default) = off. Why one might want
  /// it: on the wave front of α = 1000 the FE L2 error is 4–6× the interpolation error, and it
  /// is generated beside the front: at 2.8·10⁴ vertices (defaults) 73 % of
  /// ‖e‖²_L2 = Σ_T ∫_T ∇e·∇(z − z_h) (z: −Δz = e; scripts/front_l2_dwr.py) comes from the
  /// triangles 3·10⁻³–0.1 away from the front, which hold 12 % of the H1² error and 15 % of the
  /// triangles: there ∇e is moderate but the elements are large for the dual z. p = 2 puts more
  /// vertices there (density det|H|^(1/3) against √det|H|). Measured (run.sh's FreeFem++ loops
  /// to 2–4·10⁴ vertices, defaults otherwise, worst ratios over the cycles ≥ 5·10³, L2 / H1):
  /// steep front 1.29/0.37 → 0.92/0.38 (φ = 0.3), 0.87/0.41 (φ = 0.5; p = 2 alone: 0.85/0.43),
  /// but at φ = 0.5 the L-shape 0.85/0.96 → 0.94/0.98, the peak's H1 0.92 → 0.95 and the line
  /// singularity's L2 rate −0.79 → −0.47 (the corner's dual is singular too: p = ∞ is its
  /// L2-optimal grading, see metric above). So it is off by default.
  double l2Share = 0;
  /// γ > 0: the dual-weighted density correction (adapt/dual_weight.hpp, derivation and
  /// measurements there): in runAdaptiveLoop the graded metric is multiplied by s = (η/η̄)^γ per
  /// vertex (clamped to [½, 2]), η the dual-weighted indicator of u_h and of the unit-load dual
  /// z_h (one more solve per cycle), then rescaled to N. ¼ alone: the steep front's L2 ratio to
  /// FreeFem++ 1.29 → 0.76, the wave front's, peak's and multiple's L2 0.15–0.2 lower, H1 and the
  /// corners unchanged (±0.02); the layer's and the line singularity's L2 rates fall to −0.63 and
  /// −0.50. Default ⅛ with h1Weight ¼ (below): z's factor pulls the density towards the corners'
  /// singular dual, which costs their H1 (the L-shape's 0.893 at ¼, 0.883 at 0; the peak's H1
  /// gains from u's factor). 0 = off (and in adaptMetric, which has no problem to solve the dual of).
  double dualWeight = 0.125;
  /// γ₁ ≥ 0: the H1 density correction (adapt/dual_weight.hpp, "H1 weighting"): the density factor
  /// above also carries (ε_T/ε̄)^γ₁, ε_T = ‖G u_h − ∇u_h‖_T the Zienkiewicz–Zhu estimate of u_h's
  /// local H1 error, so the next mesh equidistributes the H1 error that the Hessian model of the
  /// current mesh mis-states (a feature not yet resolved, patch averages at a singular corner).
  /// Same clamp [½, 2] on the product; no extra solve. Default ¼ (with dualWeight ⅛, hgrad 1.5;
  /// measurements in dual_weight.hpp): the corners' worst H1 ratio to FreeFem++ 0.890–0.893 →
  /// 0.883–0.885, the slit's 0.898 → 0.893, the peak's 0.881 → 0.879; the steep front's L2 0.57 →
  /// 0.76 (the price of the lower dualWeight). 0 = off (and in adaptMetric).
  double h1Weight = 0.25;
  /// φ_z ∈ [0, 1), φ + φ_z < 1: a share of the complexity for the metric of the unit-load dual
  /// z_h (the dual of dualWeight; its recovered Hessian, the same p and bounds), intersected
  /// with u's: M(u; (1 − φ − φ_z) N) ∩ M(z; φ_z N). Why (adapt/dual_weight.hpp, "Anisotropy"):
  /// on a triangle stretched along u's flat direction the gradient error of z's interpolant
  /// across it is h_long²/h_short · |∂²z/∂long²|, so the FE L2 error's term ∇e·∇(z − z_h) grows
  /// with the aspect ratio the Hessian of u allows; M(z) bounds h_long where z is curved.
  /// Default 0.01 (measured in dual_weight.hpp); 0 = off (no dual Hessian recovery).
  double dualShare = 0.01;
  /// β ∈ [0, 1] (0: off): singular grading at reentrant corners of the boundary (gradeSingularCorners
  /// in metric_from_hessian.hpp: the corner's size becomes max(β r*, hc/4) where the sizes around it
  /// follow h = A r^σ, r* = A^(1/(1−σ))). Default ¼: the L-shape's H1 ratio to FreeFem++ 0.901 →
  /// 0.890 at 7.9·10³ vertices, the share of H1² within 10⁻⁴ of the corner 1.7 → 0.2 %
  /// (measurements there). Applied last, after the rescales to N, then graded again (hgrad), so its
  /// extra vertices are not counted: before the rescales (as it was first) the complexity integral
  /// counted the corner's small size over its large background triangles and shrank the rest of the
  /// mesh (the slit at 5·10² vertices: 433 for 540 aimed at), and the slit's corner lagged at the
  /// sizes of one pass (its worst H1 ratio at 6.8·10⁴ vertices 0.893 → 0.888, L-shape, 5π/4 and
  /// 7π/4 within ±0.002; to 10⁵ vertices, docs/experiments.md).
  double cornerGrading = 0.25;
  /// With dualShare > 0: the dual's Hessians are weighted per vertex by |tr H_u| (the recovered
  /// Laplacian of u_h) before their metric is built, M(|Δu_h| |H_z|; φ_z N) (adapt/dual_weight.hpp,
  /// "Goal weighting"): the dual's curvature bounds the long size only where ∇(u − Πu) is large.
  /// false (default): M(H_z; φ_z N).
  bool dualGoal = false;
  /// The mesher's options for the loop: the Adapt preset (mesher/mesher.hpp: lattice along the
  /// short-size direction, plateau stop, no defect annealing; the reasons are there).
  mesher::MeshOptions mesh = mesher::meshPreset(mesher::MeshPreset::Adapt);
  fem::SolveOptions solve;
  int errorDegree = 8;  ///< quadrature degree of the error norms (fem/error_norms.hpp)
  /// Stop criteria (≤ 0: off): the loop ends after the first cycle whose error is at most this.
  double stopL2 = 0, stopH1 = 0;
  /// With a stop criterion, the sizes are chosen to reach it at least cost (stopSizeAim in
  /// (0, 1]; ≤ 0: off, the schedule runs as given): after the last pass of each size, the
  /// error curve through the last two sizes (log–log) predicts the N at which each error with
  /// a stop reaches stopSizeAim × its target (the rate used is the fitted one or the optimal
  /// one, L2 N^(−1), H1 N^(−1/2), whichever is shallower, so that a pre-asymptotic steep rate
  /// does not promise too much). When that N (the largest over the criteria, at least 1.1 ×
  /// the current N) is below the schedule's next size, the next size becomes N, with the
  /// passes the schedule had there; the schedule after it is kept for a miss, where the next
  /// prediction starts from the new point (a lowered final size is followed by the original
  /// one). Without it the run goes on to whole sizes of the schedule and ends on the first one
  /// that reaches the target: with a doubling schedule the last mesh has up to 2× the vertices
  /// needed. Measured with stopRepeatMinChange (below) on `ablmg adapt --vertices 2N --stop-h1
  /// E` (examples/compare_freefem/run.sh's time to accuracy, N and E FreeFem++'s final at
  /// --maxnv 4e4, every pass run): the last mesh 8–22 % smaller (wave front 22 %, layer 19 %,
  /// line singularity 17 %, multiple 16 %, peak 14 %, the corners 8–9 %), its H1 error 0.93–0.95
  /// E instead of 0.75–0.92 E (the layer 0.85: its rate is steeper than the −1/2 used); no run
  /// missed (needed a further size); the steep front reaches E on a scheduled size (7·10³).
  double stopSizeAim = 0.95;
  /// With stopSizeAim on: when the predicted N lies beyond the schedule's next size but within
  /// stopJump × the current N (and below a later scheduled size, kept for a miss), the run goes
  /// there directly, with the passes of the first size it skips (≤ 1: off, the prediction only
  /// lowers the next size). The sizes in between only grew the mesh towards N: the metric
  /// recovered at N/16 already carries the grading and the features (the corner fits its own
  /// grading, gradeSingularCorners). On the ten problems' runs to FreeFem++'s final H1 error
  /// (`ablmg adapt --vertices 2N --stop-h1 E`), 16 cuts Σ N_k of the run by 25–45 % on nine (the
  /// layer unchanged) and every run still reaches E; the price is a last mesh 3–50 % larger than
  /// the target needs, as the prediction uses the shallower of the fitted and optimal rates.
  /// 4, 8 and 100 measured against it: docs/experiments.md, "Jumping to the predicted size".
  double stopJump = 16;
  /// Warm start: the bubbles of mesh_{k+1} start from the interior vertices of mesh_k where
  /// they fit the new metric (PlacementOptions::warmStart), the lattice filling the rest.
  bool warmStart = false;
  /// Repeated passes at one size (equal consecutive targetVertices) are run only while they can
  /// change the mesh: after a cycle whose next metric is within this metricChange of the metric
  /// the cycle's mesh was built for, the remaining passes at that size are skipped and the
  /// schedule goes on with the next size (0, the default: every pass runs). Off because the
  /// mean hides the one place where the passes matter: on the corner problems the first pass
  /// after a size doubling has metricChange 0.01–0.05 (the bulk does not move), yet each pass
  /// deepens the grading at the singular point, and skipping the repeats from 10³ vertices on
  /// (threshold 0.06) raised the L-shape's H1 error by 5–9 % at 4·10³–1.6·10⁴ vertices (H1
  /// 1.02–1.05× FreeFem's instead of 0.96; `run.sh --problem lshape --maxnv 4e4`, time to
  /// FreeFem's H1 error 0.28 of its loop). Elsewhere it is what it looks like: the wave front,
  /// the peak and the line singularity show 0.01–0.05 and errors within 2 % over the repeats;
  /// 0.2–0.8 where the passes still find a feature (steep front to 4·10³, tanh layer to 5·10³,
  /// multiple to 2·10³ vertices), with H1 errors falling by 15–60 % per pass.
  double repeatMinChange = 0;
  /// repeatMinChange for a run with a stop criterion (stopL2/stopH1) whose repeatMinChange is
  /// 0: there only the error of the last cycle counts, and what the repeats at the small sizes
  /// add (the grading at a singular point, ≤ 9 % of H1 at the intermediate sizes, see above)
  /// the larger sizes build anyway. The passes that still find a feature (metricChange 0.3–1 on
  /// the steep front and the layer up to 4·10³–5·10³ vertices, errors falling by 15–60 % per
  /// pass) are kept. Measured on the runs of stopSizeAim above, Σ N_k of the whole run, all
  /// passes → 0.2: L-shape 9.1 → 6.1·10⁴, 5π/4 9.1 → 6.1·10⁴, slit 9.9 → 6.8·10⁴, peak 10.4 →
  /// 6.9·10⁴, multiple 6.5 → 4.5·10⁴, layer 7.2 → 4.7·10⁴, steep front unchanged (2.7·10⁴),
  /// each with the same last mesh to ±2 %; 0.06 leaves the layer's, the peak's and multiple's
  /// repeats on (their dM stays at 0.07–0.3), one pass everywhere (no repeats) puts the steep
  /// front's last mesh at 1.8·10⁴ vertices instead of 7·10³. 0: every pass runs.
  double stopRepeatMinChange = 0.2;
  /// Called at each stage of each cycle (solve, recover, metric, and the mesher's stages and
  /// placement steps), with Progress::cycle and cycles set (core/progress.hpp); empty: none.
  /// The results do not depend on it.
  ProgressCallback progress;
};

/// Throws InputError naming the field and value.
void validate(const AdaptOptions& options);

/// The vertex count at which an error falling along the log–log line through (n0, e0) and
/// (n1, e1) (n0 < n1, the last two sizes of a run) reaches `target`, the line's slope replaced
/// by `optimalRate` (< 0: −1 for L2, −1/2 for H1 with P1) where that is shallower:
/// n1 (target / e1)^(1/rate). NaN when it cannot be predicted: non-positive or non-finite
/// input, n0 ≥ n1, or the errors not falling (rate ≥ −0.05). ≤ n1 when e1 ≤ target.
double verticesForError(double n0, double e0, double n1, double e1, double target, double optimalRate);

struct QualitySummary {
  double mean = 0, min = 0;  ///< of q(T) = 4√3 |T|_M / Σ |e|²_M ∈ (0, 1], 1 = equilateral in M
};
/// Mean over vertices of the largest relative change of a unit edge's length from metric `from`
/// to metric `to` at the vertex, as a logarithm: max(|ln √μ₁|, |ln √μ₂|), μ the eigenvalues of
/// from⁻¹ to. 0 when they are equal, ln 2 ≈ 0.69 when every size halves. Equal sizes required.
double metricChange(std::span<const Metric2> from, std::span<const Metric2> to);

/// Element quality in the metric the mesh was built for (per-vertex metrics, the triangle's
/// metric being the mean of its three vertices').
QualitySummary metricQuality(const Mesh2& mesh, std::span<const Metric2> metrics);

struct CycleReport {
  int cycle = 0;
  double targetVertices = 0;
  long vertices = 0, triangles = 0;
  double l2 = 0, h1 = 0, l2Interp = 0, maxVertex = 0;  ///< NaN without an exact solution
  /// ‖u − I_h u‖_L2 estimated from u_h's recovered Hessians (interpolation_error.hpp): the
  /// error measure that needs no exact solution; compare with l2Interp where both exist.
  double l2InterpEstimate = 0;
  double qMean = 0, qMin = 0;
  /// Wall seconds: the solve, the Hessian recovery of u_h, the next metric (with the unit-load
  /// dual's solve and recovery when the metric uses it: dualWeight, dualShare), the mesh.
  double tSolve = 0, tRecover = 0, tMetric = 0, tMesh = 0;
  double tAssembly = 0, tOrdering = 0, tFactor = 0;  ///< the parts of tSolve
  double tErrors = 0;                                ///< computeErrors (0 without an exact solution)
  mesher::MeshStats meshStats;                       ///< the mesher's statistics and stage times for mesh_k
  long predictedVertices = 0;                        ///< the mesher's estimate N* for mesh_k
  int gradationSweeps = 0;
  /// How far the metric recovered on mesh_k (for the next size) is from the one mesh_k was built
  /// for: metricChange(current, next) below; NaN in the last cycle.
  double metricChange = std::numeric_limits<double>::quiet_NaN();
};

struct AdaptReport {
  std::vector<CycleReport> cycles;
  /// Cycles used by the fitted rates: the last cycle of each target size (passes at one size are
  /// not points of the convergence curve), the last min(4, sizes) of them.
  int rateWindow = 0;
  double l2Rate = 0, h1Rate = 0, l2InterpRate = 0;  ///< log-log slopes vs vertices (NaN if < 2 cycles)
  double l2InterpEstimateRate = 0;                  ///< the same for l2InterpEstimate (known without exact u)
  bool errorsDecrease = false;                      ///< l2 and h1 fall from the first cycle to the last
  bool stoppedEarly = false;                        ///< a stop criterion ended the loop before `cycles`
};

/// What onCycle sees (references valid during the call only).
struct CycleData {
  const CycleReport& report;
  const Mesh2& mesh;
  const std::vector<Metric2>& meshMetric;  ///< the metric mesh_k was built for, per vertex
  const Eigen::VectorXd& u;                ///< u_h per vertex
  const fem::ErrorReport& errors;          ///< with per-element L2/H1 errors (NaN and empty
                                           ///< vectors when the problem has no exact solution)
  const std::vector<Metric2>& nextMetric;  ///< M_k per vertex of mesh_k (empty in the last cycle,
                                           ///< including one ended by a stop criterion)
};

/// What the loop solves: −∇·(κ∇u) = f on `domain` with the boundary data of `pde` (by tag:
/// the tags of the domain's loops are the tags of every mesh's boundary edges), and, when
/// known, the exact solution. Without it the error columns of the report are NaN, the rates
/// are NaN, errorsDecrease is false and stopL2/stopH1 are rejected; meshes, metrics and u_h
/// are produced as usual. Data must be functions or constants (not per-vertex values: the mesh
/// changes every cycle).
/// Several materials: `regions`, when it has triangles, is a coarse valid mesh of `domain` whose
/// triangleRefs are the subdomains and whose interfaceEdges are the interfaces between them
/// (pde.kappaBySubdomain / fBySubdomain keyed by those refs). mesh_0 is then remeshed from it
/// with the uniform metric (remesh(domain, regions, ...): subdomain by subdomain), and every
/// later mesh keeps the subdomains, their refs and the interfaces (as chains of edges);
/// the Hessians are recovered per subdomain (hessian_recovery.hpp).
struct AdaptProblem {
  Domain domain;
  fem::PoissonProblem pde;
  std::optional<fem::ExactSolution> exact;
  Mesh2 regions;
};

/// A library problem as an AdaptProblem: κ = 1, u as Dirichlet data on the whole boundary, exact u.
AdaptProblem adaptProblem(const fem::TestProblem& problem);
/// A material problem (fem/material_problems.hpp) as an AdaptProblem: no exact solution.
AdaptProblem adaptProblem(const fem::MaterialProblem& problem);

/// A reference solution for a problem without an exact one: the P1 solution of the loop run on
/// `problem` to `vertices` (geometricSchedule(vertices) with 2 passes per size, `options`' metric settings), as a
/// fem::ExactSolution (u interpolated linearly on the reference mesh's triangle containing the
/// point, ∇u that triangle's gradient; thread-safe). The loop's errors against it measure the
/// distance to that fine solution: meaningful while the loop's meshes are much coarser (≤ a
/// quarter of its vertices). The mesh and values are kept alive by the returned functions.
struct ReferenceSolution {
  fem::ExactSolution exact;
  long vertices = 0;  ///< of the reference mesh
};
ReferenceSolution referenceSolution(const AdaptProblem& problem, double vertices, const AdaptOptions& options);

/// For each of `input`'s interface edges ab, the length of ab covered by `output`'s interface
/// edges on the same line (overlaps summed, so a value above |ab| means output edges overlap
/// each other). |ab| to round-off for every edge when the interfaces are resolved. Output edges
/// are found through a bucket grid of cell = mean input interface edge length: linear time for
/// output edges no longer than the domain's extent in cells.
std::vector<double> interfaceCoverage(const Mesh2& input, const Mesh2& output);
/// Σ over `input`'s interface edges of max(0, |ab| − interfaceCoverage): the length of the
/// input's interfaces missing from the output (0 to round-off when they are resolved).
double uncoveredInterfaceLength(const Mesh2& input, const Mesh2& output);

AdaptReport runAdaptiveLoop(const AdaptProblem& problem, const AdaptOptions& options,
                            const std::function<void(const CycleData&)>& onCycle = {});
/// runAdaptiveLoop(adaptProblem(problem), options, onCycle).
AdaptReport runAdaptiveLoop(const fem::TestProblem& problem, const AdaptOptions& options,
                            const std::function<void(const CycleData&)>& onCycle = {});

/// mesh_0: meshDomain with the uniform isotropic metric of N vertices.
mesher::MeshResult uniformMesh(const Domain& domain, double targetVertices, const mesher::MeshOptions& options = {});
/// mesh_0 of `problem`: uniformMesh(domain), or with regions, the regions remeshed to that metric.
mesher::MeshResult uniformMesh(const AdaptProblem& problem, double targetVertices,
                               const mesher::MeshOptions& options = {});

/// The metric for the next mesh and how it was made.
struct AdaptedMetric {
  std::vector<Metric2> metric;  ///< one per vertex of the mesh it was computed on
  /// Lattice rows per vertex (saddleLatticeRows; empty when metric.saddleShape = 0), for
  /// BackgroundMetricField's latticeRow (runAdaptiveLoop passes them to the mesher; a metric
  /// written to a file does not carry them, so `ablmg remesh` of it has the plain lattice).
  std::vector<Vec2> rows;
  GradationStats gradation;   ///< of limitGradation (all zero when options.hgrad ≤ 1)
  double secondsRecover = 0;  ///< Hessian recovery (adaptMetric only; 0 in metricFromRecovered)
  double secondsMetric = 0;   ///< metric from the Hessians, bounds, gradation and rescale
};

/// M for the next mesh: recoverHessians → metricFromHessians(targetVertices) → gradation if
/// options.hgrad > 1, rescaled to the target complexity → singular corners (cornerGrading) and
/// gradation again, not rescaled. Per vertex of `mesh`.
AdaptedMetric adaptMetric(const Mesh2& mesh, std::span<const double> u, double targetVertices,
                          const AdaptOptions& options);

/// adaptMetric's second half, on Hessians already recovered (one per vertex of `mesh`).
/// `densityScale` (empty, or one factor > 0 per vertex): the graded metric is multiplied by it
/// and rescaled to the target complexity (dual_weight.hpp).
/// `dualHessians` (empty, or one per vertex): the recovered Hessians of the dual z_h; with
/// options.dualShare φ_z > 0 the metric is M(u; (1 − φ − φ_z) N) ∩ M(z; φ_z N) before gradation.
AdaptedMetric metricFromRecovered(const Mesh2& mesh, std::span<const Hessian2> hessians, double targetVertices,
                                  const AdaptOptions& options, std::span<const double> densityScale = {},
                                  std::span<const Hessian2> dualHessians = {});

}  // namespace ablmg::adapt
