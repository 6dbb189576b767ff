#pragma once
/// Bubble adjacency lists (paper §3.3) in compressed rows (AdjacencyLists, node_set.hpp).
///
/// Nodes i, j are adjacent iff their metric distance with the averaged tensor (eq. 3),
/// sqrt(dᵀ (M_i + M_j)/2 d), is ≤ radius (paper: 1.7σ, i.e. 1.7 in metric units since the
/// rest distance σ = l_ij + l_ji ≈ 1). The relation is symmetric by construction.
#include "ablmg/core/metric2.hpp"
#include "ablmg/mesher/node_set.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace ablmg::mesher {

/// The adjacency criterion above.
inline bool withinMetricRadius(const Vec2& d, const Metric2& mi, const Metric2& mj, double radius) {
  return 0.5 * (mi.squaredLength(d) + mj.squaredLength(d)) <= radius * radius;
}

/// Half-widths (x, y) of the bounding box of {d : dᵀ M d ≤ r²}: r·√((M⁻¹)₁₁), r·√((M⁻¹)₂₂).
/// If the averaged metric distance of a pair is ≤ r then the smaller of |d|_{M_i}, |d|_{M_j}
/// is ≤ r, so every pair lies in the box of one of its two nodes.
inline Vec2 reachBox(const Metric2& m, double r) {
  const double det = std::max(m.det(), 1e-300);
  return {r * std::sqrt(m.m22() / det), r * std::sqrt(m.m11() / det)};
}

/// Built from scratch with a bucket grid of the nodes (cells ≈ mean spacing), or a 2-d tree
/// (point_box_tree.hpp) when the grid's cells are crowded, as in a boundary layer where a
/// cell holds hundreds of nodes. Node i scans the bounding box of its ellipse
/// {d : |d|_{M_i} ≤ r}: if the averaged distance is ≤ r then one of |d|_{M_i}, |d|_{M_j} is
/// ≤ r, so the pair is found from i or from j; the rows are then symmetrised. O(N) expected
/// on the grid, O(N log N) on the tree, whatever the anisotropy or the grading. OpenMP.
AdjacencyLists buildAdjacency(std::span<const Vec2> positions, std::span<const Metric2> metrics, double radius);

/// Refresh after the bubbles moved (§3.3): candidates of i are i's list and its neighbours'
/// lists (the two-ring), re-tested at the new positions. Symmetric, since the two-ring relation
/// is. Valid while no bubble moved more than ~(radius − 1.5)/2 since `old` was built.
/// If `moved` is given (one flag per node: moved since `old` was built), only rows with a
/// moved node within two hops are recomputed (the others cannot have changed, and the two-hop
/// rule keeps the result symmetric); the result is the same as without the mask.
AdjacencyLists refreshAdjacency(const AdjacencyLists& old, std::span<const Vec2> positions,
                                std::span<const Metric2> metrics, double radius, std::span<const char> moved = {});
/// The same, in place: only the rows to recompute are touched when they fit in their row's
/// capacity (cost ∝ rows near moved nodes, not N: the dynamics refreshes up to every step).
/// The in-place functions may leave the lists with slack (AdjacencyLists::ends); compact()
/// them before comparing ids/offsets.
void refreshAdjacencyInPlace(AdjacencyLists& lists, std::span<const Vec2> positions, std::span<const Metric2> metrics,
                             double radius, std::span<const char> moved = {});

/// Local refresh for bubbles that travelled far (`centres`, ascending): their rows are
/// recomputed from the two-ring, and every other row gains or loses the changed pairs so that
/// the relation stays symmetric. The dynamics passes the bubbles' reference positions (where
/// each row was last computed; the centres' are their current ones): the lists then stay the
/// radius-lists of the reference positions, and a pair missing from them has closed in by at
/// most the two bubbles' travels since (place_nodes.cpp). The two-ring holds every partner as
/// long as no bubble is more than (radius − 1.5)/2 from its reference position: a bubble
/// between the two lies within the radius of both, unless the packing has a hole of metric
/// radius ≈ 0.8. Used when some bubbles outrun that margin (graded metrics: otherwise a global
/// refresh every ~3 steps).
void refreshAdjacencyAround(AdjacencyLists& lists, std::span<const Vec2> positions, std::span<const Metric2> metrics,
                            double radius, std::span<const int> centres);

/// After population edits: `old` lists of the previous nodes, `map` old → new id (−1 =
/// deleted; empty = identity), new bubbles are ids firstNew … positions.size()−1. Rows of
/// survivors are remapped; each new bubble searches all bubbles within its reach box, every
/// bubble the new ones within its own (the search structures of buildAdjacency), and pairs are linked both
/// ways. Equal to a rebuild when the survivors have not moved since `old` was built (the
/// dynamics passes reference positions, for which that holds). O(N) with a small constant.
AdjacencyLists patchAdjacency(const AdjacencyLists& old, std::span<const int> map, int firstNew,
                              std::span<const Vec2> positions, std::span<const Metric2> metrics, double radius);

}  // namespace ablmg::mesher
