#pragma once
/// The unsteady adaptive loop: the heat equation (fem/heat.hpp) on a mesh that follows the
/// solution, remeshed every k time steps, the state carried across by the transfer
/// (adapt/transfer.hpp).
///
/// Time is cut into intervals of k steps, [t_i, t_i + k Δt] (the last one shorter if needed).
/// For each interval, with the state S_i (u^n, and u^(n−1) for BDF2) on mesh_i:
///
///   metric = Interval (default; F. Alauzet, A. Loseille et al., the transient fixed point:
///            "Time-accurate anisotropic mesh adaptation for three-dimensional time-dependent
///            problems with body-fitted moving geometries", JCP 331 (2017), and Alauzet, Frey,
///            George, Mohammadi, "3D transient fixed point mesh adaptation for time-dependent
///            problems", JCP 222 (2007)):
///              candidate = mesh_i;
///              repeat fixedPointIterations times:
///                solve the interval on the candidate from S_i (transferred),
///                H_max = ∩_j |H(u(t_j))| over the interval's sub-steps j = 0, s, 2s, …, k
///                        (s = hessianEvery; metric intersection of the recovered Hessians,
///                        vertex-wise on the candidate),
///                candidate = remesh(metricFromRecovered(H_max, N));
///              the metric thus covers the feature over the whole interval, not only at t_i;
///   metric = Current: the metric of u(t_i) alone (one remesh, no interval solve): the
///            classic loop, whose mesh is right at t_i and late by t_i + kΔt.
///   then: transfer S_i to the candidate (it becomes mesh_(i+1)), solve the interval there;
///   those steps are the ones reported.
/// The target N is the vertex count of every mesh (metricFromRecovered: complexity (√3/2) N
/// after the hmin/hmax bounds); the intersection is of the un-normalised Hessians, so the
/// metric of an interval has the same complexity as one of a single time.
/// Defaults k = 20 (a remesh every 0.02 time units at the problems' dt 0.001: the feature moves
/// about half its width per interval), one fixed-point pass: at dt 0.002 and N = 4000, k = 5
/// with two passes had a 5 % smaller space-time error than k = 10 with one for 3.6× the CPU
/// time on the moving peak (the remeshes dominate), and a second pass did not help the front.
/// uniform = true: one isotropic mesh of N vertices (adapt::uniformMesh), never remeshed: the
/// comparison run. The initial state is the nodal interpolant of the exact u(t0) on the mesh
/// the first interval is solved on.
///
/// Errors, per step t_n (n ≥ 1), by fem::computeErrors against the exact u(·, t_n):
///   l2(t_n) = ‖u − u_h‖_L2,  h1(t_n) = |u − u_h|_H1;
///   space-time L2 = (Σ_n Δt l2(t_n)²)^(1/2),  L2(H1) = (Σ_n Δt h1(t_n)²)^(1/2)   (accumulated).
/// Deterministic: every stage is (same options ⇒ same bits, any thread count); times are wall
/// seconds and the only varying numbers. Every mesh is validated (Mesh2::validate with the
/// domain's area; ablmg::Error if one is not valid).
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/transfer.hpp"
#include "ablmg/fem/heat.hpp"
#include "ablmg/fem/transient_problems.hpp"

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace ablmg::adapt {

enum class TransientMetric { Interval, Current };
/// "interval" / "current" ↔ TransientMetric (InputError naming the valid names).
TransientMetric parseTransientMetric(const std::string& name);
std::string toString(TransientMetric m);

struct TransientOptions {
  double dt = 0;                                           ///< > 0; 0 = the problem's
  double tEnd = std::numeric_limits<double>::quiet_NaN();  ///< > the problem's tStart; NaN = the problem's
  int remeshEvery = 20;                                    ///< k ≥ 1 steps per interval
  double vertices = 4000;                                  ///< N, vertices of every mesh (≥ 10)
  int fixedPointIterations = 1;                            ///< ≥ 1 (Interval metric)
  /// The Interval metric intersects the Hessians of the sub-steps j = 0, s, 2s, … and the
  /// interval's last step (s ≥ 1). Each recovery costs about as much as a time step's solve;
  /// at s = 2 a feature moves 0.05–0.07 of its width between samples on the library's problems.
  int hessianEvery = 2;
  TransientMetric metric = TransientMetric::Interval;
  bool uniform = false;  ///< fixed uniform mesh of N vertices
  fem::TimeScheme scheme = fem::TimeScheme::BDF2;
  TransferOptions transfer;  ///< L2 projection by default
  /// Hessian method, metric norm/p/bounds, gradation and mesher options of the steady loop
  /// (adaptive_loop.hpp); targetVertices there is ignored (N above is used). The unsteady loop
  /// keeps the L2 metric (p = 2) without gradation, the settings its defaults were measured
  /// with; the steady loop's own defaults (p = ∞, hgrad 1.3) are chosen for singular points.
  AdaptOptions adapt = [] {
    AdaptOptions a;
    a.metric.p = 2;
    a.metric.shapeBlend.reset();  // the Lp shape, as measured
    a.hgrad = 0;
    return a;
  }();
  int errorDegree = 5;  ///< quadrature degree of the errors (1…8)
};

/// Throws InputError naming the option and the value ("transient options: remeshEvery must be
/// >= 1 (got 0)", "dt must be > 0", "tEnd (0.1) must be after the start time (0.2)", ...).
/// `tStart` is the problem's start time.
void validate(const TransientOptions& options, double tStart);

struct StepRecord {
  int step = 0;  ///< n ≥ 1
  double time = 0;
  long vertices = 0;
  double l2 = 0, h1 = 0;  ///< at t_n
};

/// One row per interval (per remesh; interval 0 starts from the initial mesh).
struct IntervalRecord {
  int interval = 0;
  double time = 0;  ///< the interval's start t_i (the remesh time)
  double timeEnd = 0;
  long vertices = 0, triangles = 0;
  /// ‖u − u_h‖_L2 at t_i on the new mesh, right after the transfer (interval 0: the error of the
  /// interpolated initial state)
  double l2AtStart = 0;
  double l2AtEnd = 0;                                          ///< at the interval's end
  double spaceTimeL2 = 0, spaceTimeH1 = 0;                     ///< accumulated up to the interval's end
  double massDefect = 0;                                       ///< relative, of the kept transfer (0 when none)
  double tRemesh = 0, tTransfer = 0, tSolve = 0, tMetric = 0;  ///< wall seconds, all passes of the interval
  int passes = 0;                                              ///< interval solves (fixed-point + kept)
};

struct TransientReport {
  std::vector<IntervalRecord> intervals;
  std::vector<StepRecord> steps;
  double spaceTimeL2 = 0, spaceTimeH1 = 0;
  double averageVertices = 0;  ///< over the steps
  double maxL2 = 0;            ///< largest l2(t_n)
  double maxMassDefect = 0;    ///< largest relative mass defect of a transfer
  double dt = 0, tStart = 0, tEnd = 0;
  int meshes = 0;      ///< distinct meshes built (all validated)
  double seconds = 0;  ///< wall time of the loop
};

/// What the callbacks see (valid during the call only).
struct TransientFrame {
  const IntervalRecord& record;  ///< the interval just solved (its fields complete)
  const Mesh2& mesh;             ///< its mesh
  const Eigen::VectorXd& u;      ///< u_h at record.timeEnd
};

/// Runs the loop on a library problem (its κ, f, u as Dirichlet data, u(t0) as initial state).
/// onInterval is called after each interval.
TransientReport runTransientLoop(const fem::TransientProblem& problem, const TransientOptions& options,
                                 const std::function<void(const TransientFrame&)>& onInterval = {});

/// Vertex-wise metric intersection of the absolute recovered Hessians (the H_max above):
/// `accumulated` is empty (then set to |h|) or one per vertex. |λ| floored at 1e−12 × the
/// largest |λ| of `h` so that every tensor is SPD.
void intersectHessians(std::vector<Hessian2>& accumulated, std::span<const Hessian2> h);

}  // namespace ablmg::adapt
