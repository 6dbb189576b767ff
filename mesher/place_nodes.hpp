#pragma once
/// Node placement by elliptical bubble simulation (paper §3): the driver.
///
///   initial placement (§3.1) → [ dynamics, eq. (5)–(8) (§3.2) ↔ population control, eq. (9)
///   (§3.4) ] with adjacency lists (§3.3) → stop rule → PlacementResult
///
/// Schedule: population passes (population.hpp) every 10 steps, each after an adjacency
/// refresh, until two passes in a row change nothing (or 60 % of maxSteps); the run stops when
/// the residual < tolerance after that, or when the residual has not halved for stallSteps
/// steps (stats.stalled), or at maxSteps. Boundary nodes are placed once (equal metric length
/// per piece between corners) and keep their count; only interior bubbles are inserted/deleted.
///
/// Measured (Domain::disk({0,0},10), the three §4.3 metrics, defaults, 1 thread): final count
/// vs N* −1.8 % / −3.7 % / −1.1 %; interior nearest-neighbour metric distance in
/// [0.85, 1.15] for 99.8 % / 98.0 % / 97.6 %; residual drop ×438 / ×808 / ×606 in 823 / 1277 /
/// 860 steps; boundary edges of metric length 1.000–1.001 (tests/mesher/test_place_nodes.cpp).
///
/// Early stopping (issue 7): `tolerance` trades steps for packing quality: on the constant
/// metric at 10⁵ nodes, 1e-3 takes ~980 steps, 1e-2 ~390 (bench/bench_place_nodes.cpp).
///
/// Speed (issue 7; 1 thread, CPU seconds on the shared 2-core machine, bench/bench_place_nodes
/// with tol 1e-2): constant metric on the radius-10 disk, 10⁵ nodes 2.6 s (3.7 s before the
/// issue-7 work), 10⁶ nodes 19.9 s (29.0 s), 387 / 589 steps, 36 % / 13 % of the bubbles awake per
/// step. Wave-front 12k remesh (`ablmg adapt --problem wavefront --target-vertices 3000,12000`):
/// 2.8 s (13.2 s: it ran to maxSteps; the stall rule stops it at ~680 steps, same quality).
/// On a loaded machine OpenMP's default busy-wait makes 2 threads far slower than 1 (seconds
/// per run lost in barriers); OMP_WAIT_POLICY=passive avoids that.
///
/// Deterministic: same domain, metric and options (seed) ⇒ bit-identical result, for any
/// number of threads (no floating reductions across threads; nothing random is drawn).
#include "core/domain.hpp"
#include "core/metric_field.hpp"
#include "mesher/node_set.hpp"

#include <cstdint>
#include <vector>

namespace ablmg::mesher {

struct PlacementOptions {
  double k0 = 1.0;            ///< force constant of eq. (7), paper §6
  double mass = 1.0;          ///< m of eq. (5), paper §6
  /// c and Δt: the paper's §6 values are c = 3.8429, Δt = 0.02. Our forces act in metric
  /// units (bubble_system.hpp), where one pair has stiffness |f'(1)| = k0 and forward Euler is
  /// stable up to Δt ≈ 0.5; with the paper's values the disk cases of §4.3 reduced the largest
  /// force only ×3–5 in 400 steps (over-damped soft modes, tiny steps), with c = 1, Δt = 0.3
  /// ×600–850 in ≤ 1400 steps. Set damping = 3.8429, timeStep = 0.02 for the paper's run.
  double damping = 0.4;       ///< c of eq. (5) (paper §6: 3.8429, see above)
  double timeStep = 0.45;     ///< Δt of the forward-Euler step (paper §6: 0.02; dimensionless, see above)
  double adjacencyRadius = 1.7;  ///< w-radius of the adjacency lists, paper §3.3
  int adjacencyRefresh = 100; ///< refresh the lists every k steps (§3.3), or earlier when a bubble travelled (radius − 1.5)/2
  int maxSteps = 2000;        ///< cap on dynamics steps; stats.hitStepCap says if it was hit
  /// Convergence: stop when the residual (largest net force |f_i|_{M_i}, metric units; see
  /// bubble_system.hpp) has dropped below max(tolerance, relativeTolerance × initial residual),
  /// checked with every bubble awake, once the population has settled. The relative part is
  /// the early-stopping knob of issue 7 (README "Speed": time vs quality table).
  double tolerance = 1e-3;
  double relativeTolerance = 1e-2;
  /// Stall rule (0 = off): stop when the residual has not halved within this many steps
  /// (stats.stalled). Converging runs halve it every ~100 steps, with plateaus of up to ~450
  /// (paper disks: unaffected at 500, the line case stops early at 300); graded metrics from
  /// a solver may never reach `tolerance` (wave-front 12k remesh: residual 0.01–1 until
  /// maxSteps; stopped at ~680 steps instead of 2000 with the same mean/min element quality).
  int stallSteps = 150;
  long maxNodes = 50'000'000; ///< refuse (InputError, before allocating) if the estimate N* exceeds this
  std::uint64_t seed = 1;     ///< for any randomised choice; same seed, same nodes
  int threads = 0;            ///< 0 = OpenMP default
  bool bubblesOnly = false;   ///< informational: callers that only want the packing
};

struct PlacementStats {
  /// N* = (2/√3) ∫ √det M dA + Nb/2 + 1 − holes (Nb boundary nodes): by Euler, a triangulation
  /// with T unit equilateral triangles (area √3/4 each in the metric) has T = 2N − Nb − 2 + 2·holes.
  long predictedNodes = 0;
  long initialNodes = 0, finalNodes = 0;
  long inserted = 0, deleted = 0;
  int steps = 0;
  long activeBubbleSteps = 0;  ///< Σ over steps of the bubbles awake (the dynamics' real work; see BubbleSystem::updateActivity)
  bool hitStepCap = false;
  bool stalled = false;        ///< stopped by the stall rule (PlacementOptions::stallSteps)
  double initialResidual = 0, finalResidual = 0;  ///< largest net bubble force in metric units (= c × terminal velocity)
  double secondsInitial = 0, secondsDynamics = 0, secondsAdjacency = 0, secondsPopulation = 0;
};

struct PlacementResult {
  NodeSet nodes;
  AdjacencyLists adjacency;            ///< final lists, radius adjacencyRadius (metric sense)
  std::vector<Metric2> metrics;        ///< the metric at each node's final position
  std::vector<BoundaryEdge> boundaryEdges;  ///< node ids along every loop, domain on the left, with segment tags
  PlacementStats stats;
};

PlacementResult placeNodes(const Domain& domain, const MetricField& metric, const PlacementOptions& options = {});

} // namespace ablmg::mesher
