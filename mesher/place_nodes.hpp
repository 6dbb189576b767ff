#pragma once
/// Node placement by elliptical bubble simulation (paper §3): the driver.
///
///   initial placement (§3.1) → [ dynamics, eq. (5)–(8) (§3.2) ↔ population control, eq. (9)
///   (§3.4) ] with adjacency lists (§3.3) → stop rule → PlacementResult
///
/// Schedule: population passes (population.hpp) every 10 steps until two passes in a row
/// change at most 1 node in 10⁴ (or 60 % of maxSteps), steering the count up to 1.01 N* until
/// it stops growing for 4 passes (population.hpp); once the population has settled, a few
/// defect-annealing passes (defects.hpp, PlacementOptions::defectPasses); the run stops when the residual has
/// dropped below max(tolerance, relativeTolerance × initial) with every bubble awake, or when
/// it has not halved for stallSteps steps (stats.stalled: graded metrics from a solver, where a
/// few bubbles keep jolting), or at maxSteps. Boundary nodes are placed once (equal metric
/// length per piece between corners) and keep their count; only interior bubbles are edited.
///
/// Adjacency upkeep (§3.3): lists of radius 1.7 are exact for the force and eq. (9) (both end
/// at w = 1.5) while no pair has closed in by more than 0.2, so each bubble's travel since its
/// row was last computed is tracked; the rows of the bubbles that travelled more than 0.1 are
/// recomputed after each step, at the reference positions (place_nodes.cpp), and mirrored
/// (adjacency.hpp), a full refresh when they are more than a quarter of all; plus a full
/// refresh every adjacencyRefresh steps.
///
/// The stop rules and schedules are placement_schedule.hpp's. Speed: the dynamics parameters
/// c = 0.35, Δt = 0.45 and the active set (bubble_system.hpp) make a constant metric converge
/// (×100) in about 100 steps at 4·10³ nodes and about 220 at 5·10⁵ (docs/benchmarks.md). On
/// a loaded machine OpenMP's default busy-wait makes 2 threads far slower than 1;
/// OMP_WAIT_POLICY=passive avoids that.
///
/// Output: no two nodes share a point (node_set.hpp, coincidentNodes). Deterministic: same
/// domain, metric and options ⇒ bit-identical result, for any number of threads (no floating
/// reductions across threads; the seed's draws depend on the seed and the node only).
#include "ablmg/core/domain.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/core/progress.hpp"
#include "ablmg/mesher/bubble_force.hpp"
#include "ablmg/mesher/initial_placement.hpp"
#include "ablmg/mesher/node_set.hpp"

#include <cstdint>
#include <vector>

namespace ablmg::mesher {

struct PlacementOptions {
  double k0 = 1.0;    ///< force constant of eq. (7), paper §6
  double mass = 1.0;  ///< m of eq. (5), paper §6
  /// c and Δt: the paper's §6 values are c = 3.8429, Δt = 0.02. Our forces act in metric
  /// units (bubble_system.hpp), where one pair has stiffness |f'(1)| = k0 and the semi-implicit
  /// Euler step is stable up to Δt ≈ 0.6 for a hexagonal packing; with the paper's values the
  /// disk cases of §4.3 reduced the largest force only ×3–5 in 400 steps (over-damped soft
  /// modes, tiny steps); c = 0.35, Δt = 0.45 converge in 100–210 steps on the four paper
  /// cases with the same or better edge statistics (docs/benchmarks.md). Set damping = 3.8429,
  /// timeStep = 0.02 for the paper's own run.
  double damping = 0.35;   ///< c of eq. (5) (paper §6: 3.8429, see above)
  double timeStep = 0.45;  ///< Δt of the forward-Euler step (paper §6: 0.02; dimensionless, see above)
  /// w of the pair force: eq. (8) (default, the paper's), or the eq. (3) averaged-metric
  /// length; bubble_force.hpp has the measurements (mesh quality vs the layer's H1 error).
  PairDistance pairDistance = PairDistance::Harmonic;
  double adjacencyRadius = 1.7;  ///< w-radius of the adjacency lists, paper §3.3
  int adjacencyRefresh =
      100;  ///< refresh the lists every k steps (§3.3), or earlier when a bubble travelled (radius − 1.5)/2
  int maxSteps = 2000;  ///< cap on dynamics steps; stats.hitStepCap says if it was hit
  /// Convergence: stop when the residual (largest net force |f_i|_{M_i}, metric units; see
  /// bubble_system.hpp) has dropped below max(tolerance, relativeTolerance × initial residual),
  /// checked with every bubble awake, once the population has settled. The relative part is
  /// the early-stopping knob (docs/benchmarks.md: time against quality).
  double tolerance = 1e-3;
  double relativeTolerance = 1e-2;
  /// Stall rule (0 = off): stop when the residual has not halved within this many steps
  /// (stats.stalled). The paper disks halve it every ≤ 60 steps and are unaffected; metrics
  /// from a solver may never settle, and stop with the quality they would have hundreds of
  /// steps later.
  int stallSteps = 150;
  /// Quality plateau (0 = off): stop when the share of neighbour pairs within ±10 % of unit
  /// metric length (sampled every 10 steps; plateauSteps is rounded up to a multiple of 10)
  /// has gained less than plateauGain over the last plateauSteps steps and the residual has
  /// not halved in as many (stats.qualityPlateau). Sampling starts
  /// once the population has settled or its last pass edited ≤ 0.2 % of the nodes (graded
  /// metrics keep editing a few per mille for hundreds of steps). The early-stopping knob for
  /// graded metrics, whose residual may never settle. Off by default (a converged packing:
  /// the constant-metric disk would stop at ×65 instead of ×100). `ablmg remesh` and the
  /// adaptive loop use 10 steps and a gain of 1 point (adapt/remesh.hpp, adaptive_loop.hpp).
  int plateauSteps = 0;
  /// When the stall or plateau rule fires fewer than this many steps after the last
  /// population edit or defect kick, the run goes on without edits until that many steps have
  /// passed since it (a graded remesh can stall one step after a pass of hundreds of edits).
  int finalRelaxSteps = 10;
  double plateauGain = 0.002;  ///< share gain (0.002 = 0.2 point) that counts as progress
  /// A bubble's metric is evaluated again once it has moved this far (metric units) from where
  /// it was last evaluated; the output metrics are exact. Under a background mesh the
  /// evaluation (point location + log-Euclidean interpolation) is ~25 % of a dynamics step.
  double metricLag = 0.1;
  /// Defect annealing (defects.hpp): once the population has settled, up to defectPasses
  /// passes, defectEvery steps apart, kick the lattice defects (nodes of degree ≠ 6 in their
  /// metric's Voronoi cell) and their neighbours by defectShake metric units; the run then
  /// converges as before. Skipped when at most defectMinShare of the interior nodes are
  /// defects (the constant disk: boundary dislocations that stay). On the paper disks it
  /// adds 1–3 points of edges within ±10 % for about ×1.5 steps (docs/benchmarks.md). Runs
  /// that stop on the quality plateau before the population settles are unchanged. 0 = off.
  int defectPasses = 6;
  int defectEvery = 20;      ///< steps between passes (the last one relaxes to convergence)
  double defectShake = 0.3;  ///< kick, metric units, in [0, 0.5] (0.4 already melts the packing)
  double defectMinShare = 0.05;
  long maxNodes = 50'000'000;  ///< refuse (InputError, before allocating) if the estimate N* exceeds this
  /// 0: the initial interior nodes as placed (§3.1). s > 0: each is first moved by a draw
  /// uniform in its metric disk of radius 0.1 (place_nodes.cpp, jitterInterior; a move that
  /// would come within 0.5 of the boundary is not made), so two seeds give two different
  /// meshes of the same statistics, e.g. to see how much a result owes to one mesh. Same seed,
  /// same nodes, on any thread count.
  std::uint64_t seed = 0;
  int threads = 0;  ///< 0 = OpenMP default
  /// Not read by placeNodes: a request to callers that mesh (`ablmg mesh` then writes the
  /// packing, the bubbles over the domain, instead of connecting it).
  bool bubblesOnly = false;
  /// Warm start: interior seed positions, e.g. the previous mesh's vertices in an
  /// adaptive loop; those that fit the metric's spacing replace lattice points (empty = cold).
  /// The relative target then refers to max(initial residual, 0.5), a fresh lattice's typical
  /// initial residual, not to the warm packing's own (already small) one.
  std::vector<Vec2> warmStart;
  /// The initial interior lattice (initial_placement.hpp): spacing rules and orientation.
  InteriorPlacementOptions lattice;
};

struct PlacementStats {
  /// N* = (2/√3) ∫ √det M dA + Nb/2 + 1 − holes (Nb boundary nodes): by Euler, a triangulation
  /// with T unit equilateral triangles (area √3/4 each in the metric) has T = 2N − Nb − 2 + 2·holes.
  long predictedNodes = 0;
  long initialNodes = 0, finalNodes = 0;
  long inserted = 0, deleted = 0;
  int steps = 0;
  long activeBubbleSteps =
      0;  ///< Σ over steps of the bubbles awake (the dynamics' real work; see BubbleSystem::updateActivity)
  bool hitStepCap = false;
  bool stalled = false;         ///< stopped by the stall rule (PlacementOptions::stallSteps)
  bool qualityPlateau = false;  ///< stopped by the quality-plateau rule (PlacementOptions::plateauSteps)
  double nearestInRange = 0;  ///< nearestNeighbourShare(result): interior nodes with a nearest neighbour at 0.85–1.15
  double initialResidual = 0,
         finalResidual = 0;    ///< largest net bubble force in metric units (= c × terminal velocity)
  long coincidentDropped = 0;  ///< nodes dropped at the output for sitting on another node's point (node_set.hpp)
  int defectPasses = 0;        ///< defect annealing passes done (PlacementOptions::defectPasses)
  /// Defect nodes (degree ≠ 6) at the first and the last pass; −1 if none. Estimated from a
  /// sample of 1.3·10⁵ nodes (× the sampling stride) above 2.6·10⁵ nodes when no kick followed.
  long defectsFirst = -1, defectsLast = -1;
  double secondsInitial = 0, secondsDynamics = 0, secondsAdjacency = 0, secondsPopulation = 0;
  double secondsDefects = 0;  ///< defect annealing (topology, kicks, adjacency rebuilds)
};

struct PlacementResult {
  NodeSet nodes;
  AdjacencyLists adjacency;                 ///< final lists, radius adjacencyRadius (metric sense)
  std::vector<Metric2> metrics;             ///< the metric at each node's final position
  std::vector<BoundaryEdge> boundaryEdges;  ///< node ids along every loop, domain on the left, with segment tags
  PlacementStats stats;
};

/// Throws InputError "placement options: <field> ..." naming the field and its value: every
/// count and tolerance ≥ 0, k0, mass, timeStep > 0, threads ≥ 0 (0 = OpenMP's default), the
/// ranges documented above. placeNodes() runs it; configuration readers run it at read time.
void validate(const PlacementOptions& options);

/// Places the nodes (see above); options are validate()d first.
/// `progress` (core/progress.hpp), if set, is called every `progressEvery` steps (< 1 counts as
/// 1) with the step, the residual and its target and the node count; the result does not
/// depend on it.
PlacementResult placeNodes(const Domain& domain, const MetricField& metric, const PlacementOptions& options = {},
                           const ProgressCallback& progress = {}, int progressEvery = 10);

/// The packing figure: the share of interior nodes whose nearest neighbour in the
/// adjacency lists is at a metric distance (eq. 3, averaged tensor) in [lo, hi]; a unit
/// hexagonal packing has every node at 1. 1 when there is no interior node. O(Σ list sizes).
double nearestNeighbourShare(const PlacementResult& result, double lo = 0.85, double hi = 1.15);

}  // namespace ablmg::mesher
