#pragma once
/// A local quality post-pass on the worst triangles of a valid mesh (after the ABLMG
/// connection, mesher.hpp): edge swaps, vertex relocation and edge collapses where the
/// element quality
///   q(T) = 4√3 |T|_M / Σ|e|²_M ∈ (0, 1],  M = the mean of T's three vertex metrics
/// (quality.hpp's triangleQuality, the q that `ablmg stats` and the adaptive loop report)
/// is below a threshold. The bulk of the mesh (q ≥ threshold) is not touched.
///
/// Each pass visits the triangles with q < qThreshold, worst first (ties: lower id); a triangle
/// still bad when its turn comes gets the best of three edits (judged by the smallest q among
/// the triangles the edit changes; a tie goes to the earlier in this list), if any is possible:
///  (a) a swap: the flip of one of its interior edges (never a boundary edge; both triangles
///      with the same triangleRef) whose quadrilateral is strictly convex (exact orient2d: both
///      new triangles counter-clockwise) and which raises the smaller q of the two triangles by
///      more than `swapMargin` (no cycling); the best of its three edges;
///  (b) a move: one of its interior vertices (on no boundary edge) goes to the best of: points
///      on the segments towards the mean of the ring's ideal apexes (the apex that makes a ring
///      edge an equilateral triangle of the metric), towards the ring's centroid and towards
///      the worst star triangle's ideal apex, refined by a compass search in the vertex's
///      metric. "Best": the highest min(star's smallest q, qThreshold), then the most star
///      edges within ±10 % of unit length, then the highest smallest q (so that where the
///      metric varies fast, shape is not bought with edge lengths once the threshold is met).
///      A point is admissible only if every star triangle stays strictly counter-clockwise
///      (exact orient2d); its metric is `field.at(point)`; the move must raise the star's
///      smallest q by more than `moveMargin`;
///  (c) a collapse (if collapseEdges): its shortest edge a–b (metric length), both ends
///      interior, merges into one vertex placed as in (b) (tried from a, b and their metric
///      midpoint); the two triangles on a–b and vertex b disappear. Allowed only if the rings
///      of a and b share exactly the two apexes of a–b (no fold), all triangles around a and b
///      have one triangleRef, every new triangle is strictly counter-clockwise (exact orient2d)
///      and the smallest q of the changed triangles rises by more than `collapseMargin`. This
///      fixes the clusters of too-close nodes that no move can spread.
/// Passes stop when one changes nothing, no triangle is bad, or after maxPasses. No edit lowers
/// the smallest q of the triangles it changes or removes, so the mesh's q min never decreases.
/// (Splits of long edges were tried as well and never won on the benchmarks: left out.)
///
/// Invariants: the mesh stays valid (Mesh2::validate) and covers the same region; boundary
/// vertices (positions), boundary edges (and their refs) are unchanged; only triangles near
/// bad ones change. Collapses remove interior vertices (2 triangles each, ImproveStats::
/// collapses): the survivors keep their relative order, ids shift down past removed ones
/// (boundary edges renumbered to match), and `metrics` shrinks with the vertices (one per
/// vertex on return). The result is deterministic (single thread, fixed order): the same
/// input gives a bit-identical output. Cost: O(N) to build the triangle adjacency (counting
/// sort of half-edges, Mesh2::triangleNeighbours) and the qualities, then O(bad triangles ×
/// star size × field evaluations (≤ 140 per vertex or collapse tried)) per pass, and O(N) to
/// compact after a collapse; a move or collapse search that failed is not repeated until a
/// triangle it depends on changes (same result, less work on stuck triangles). With no bad
/// triangle, one O(N) quality scan and nothing else.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include "ablmg/core/metric_field.hpp"

#include <vector>

namespace ablmg::mesher {

struct ImproveOptions {
  bool enabled = true;           ///< meshDomain runs the pass (improveQuality itself ignores it)
  double qThreshold = 0.85;      ///< triangles with q below this are improved; in (0, 1]. 0.85 gives
                                 ///< q min 0.85 on the remesh benchmark, ±10 % share kept (docs/method.md)
  int maxPasses = 8;             ///< cap on swap + relocation passes, ≥ 0
  double swapMargin = 1e-3;      ///< a swap must raise min q of its two triangles by more (no cycling)
  double moveMargin = 1e-4;      ///< a move must raise min q of its star by more
  bool collapseEdges = true;     ///< (c) collapses of short interior edges (each removes a vertex)
  double collapseMargin = 1e-3;  ///< a collapse must raise min q of the triangles it changes by more
};

/// Throws InputError naming the first field out of range ("improve options: qThreshold ...").
void requireValid(const ImproveOptions& options);

struct ImproveStats {
  long badBefore = 0, badAfter = 0;      ///< triangles with q < qThreshold
  long swaps = 0, moves = 0;             ///< edge flips and vertex relocations done
  long collapses = 0;                    ///< interior edges collapsed (each removes a vertex, two triangles)
  int passes = 0;                        ///< passes run (≤ maxPasses)
  double qMinBefore = 0, qMinAfter = 0;  ///< smallest q over the mesh (0 for an empty mesh)
  double seconds = 0;
};

/// Improves `mesh` in place. `mesh` must be valid, `metrics` one per vertex (the prescribed
/// metric there; InputError otherwise) and `field` the metric the mesh was built for: a moved
/// vertex gets `field.at(new position)` in `metrics`; a collapsed one leaves `metrics` with the
/// mesh. Options out of range: InputError.
ImproveStats improveQuality(Mesh2& mesh, std::vector<Metric2>& metrics, const MetricField& field,
                            const ImproveOptions& options = {});

}  // namespace ablmg::mesher
