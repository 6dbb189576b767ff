#pragma once
/// Population control (paper §3.4): the overlap ratio of eq. (9) and one insertion/deletion pass.
///
/// eq. (9): α_i = Σ_j max(0, (2 l_ij + l_ji − D_ij) / l_ij) over i's adjacency list. With the
/// bubble convention of bubble_force.hpp (l_ij = 0.5·l/|d|_{M_i}) each term is
/// 2 + a/b − 2a, a = |d|_{M_i}, b = |d|_{M_j}: 1 for touching bubbles, > 1 overlapping, 0 at
/// w ≈ 1.5. The max(0, ·) keeps far members of the 1.7-radius list from counting negatively.
/// Ideal: 6 for an interior node of a hexagonal packing (≈ 4 on a straight boundary).
///
/// Thresholds (interior nodes only; boundary nodes are already placed at equal metric
/// spacing and their count is fixed):
///  - delete where α > deleteAbove (default 8: more than two extra overlapping neighbours,
///    i.e. a bubble squeezed into a full ring of 6), insert where α < insertBelow (default 4:
///    two missing neighbours, a hole at least one bubble wide);
///  - steering towards the node count N* (place_nodes.hpp) raised by `targetMargin`: while
///    the count is below that aim, the insertion threshold is relaxed to steerInsertBelow =
///    5.8 and an insertion point may be as close as steerMinGap = 0.65 to the node's
///    neighbours; while it is more than `steerTolerance` (relative) above, the deletion
///    threshold is relaxed to steerDeleteAbove = 6.7; at most |N − aim| nodes are edited. The
///    eq. (9) thresholds alone leave graded metrics several % short (the ratio is local: a
///    lattice stretched uniformly by 3 % still counts α ≈ 5.6 everywhere, and has no point
///    0.85 from all neighbours of a node), and a short packing is a stretched one, with fewer
///    edges near unit length (docs/benchmarks.md, ring metric of §4.3). steerMinGap trades the
///    node count against close pairs: a smaller gap inserts more nodes but leaves more interior
///    nodes with a neighbour closer than 0.85.
///    The margin: triangles next to lattice defects are not equilateral (q mean ≈ 0.987 on
///    the ring), so they cover less metric area than N*'s unit triangles and a real mesh needs
///    slightly more nodes.
///    Steering up ends for good (`steerUp` = false, set by the driver) once the count has
///    grown by less than `steerMinGrowth` over `steerWindow` passes: past that point the
///    packing squeezes out (squeeze rule) about as many nodes as the steering inserts, and that
///    churn kept the ring's residual from ever halving (the stall rule stopped it unconverged
///    at ×0.15–0.19). The tolerance is for graded metrics whose churn nets a little growth: the
///    tanh layer's remesh (anisotropy 10⁴, 9.5·10⁴ nodes) edited 0.45 % of its nodes every pass
///    for +0.05 %, so the population never nearly settled, the quality plateau never armed and
///    the stall rule stopped it after 177 steps; with 0.5 % steering ends after 90 steps, the churn
///    with it, and the plateau stops it at 110 (docs/experiments.md, "Population churn").
/// Insertions go to the best of twelve candidate points at metric distance 1 around the node
/// (the one farthest, in M_i, from the node's neighbours); deletions and insertions are
/// taken in order of α (ties by id) and lock the node's neighbours for the rest of the pass,
/// so one gap or overlap gets one edit. Deterministic.
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/bubble_system.hpp"

#include <vector>

namespace ablmg::mesher {

/// eq. (9) for every node.
std::vector<double> overlapRatios(std::span<const Vec2> positions, std::span<const Metric2> metrics,
                                  const AdjacencyLists& adj);

struct PopulationOptions {
  double deleteAbove = 8.0, insertBelow = 5.3;
  double squeezeBelow = 0.8,
         squeezeAlpha = 6.3;  ///< also delete where the nearest neighbour is closer than this and α above that
  double minGap = 0.85;       ///< an insertion point must be at least this far (metric) from the node's neighbours
  double steerDeleteAbove = 6.7, steerInsertBelow = 5.8;
  double steerMinGap = 0.65;     ///< minGap while steering up (below the aim)
  double steerTolerance = 0.01;  ///< steer down only when more than this (relative) above the aim
  double targetMargin = 0.01;    ///< aim = (1 + targetMargin) · target (see above)
  long target = -1;              ///< N*; < 0 = no steering
  bool steerUp = true;           ///< steering up allowed (placeNodes clears it, see steerWindow)
  /// Steering up ends once the count has grown by less than steerMinGrowth (relative) over the
  /// last steerWindow passes (PopulationSchedule, see above).
  int steerWindow = 4;
  double steerMinGrowth = 0.005;
};

struct PopulationChange {
  long inserted = 0, deleted = 0;
  std::vector<int> map;  ///< old id → new id (−1 = deleted); empty if nothing was deleted
  int firstNew = 0;      ///< inserted bubbles are ids firstNew … size−1 (appended)
};

/// One pass over `sys` (adjacency `adj` must match its current nodes). Metrics of inserted
/// nodes are evaluated (serially). After a change, the caller updates the adjacency lists
/// (patchAdjacency with `map` and `firstNew`, or a rebuild).
PopulationChange adjustPopulation(BubbleSystem& sys, const AdjacencyLists& adj, const DomainGeometry& geo,
                                  const MetricField& metric, const PopulationOptions& options);

}  // namespace ablmg::mesher
