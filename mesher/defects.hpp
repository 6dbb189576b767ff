#pragma once
/// Lattice defects of a bubble packing and their removal by local annealing.
///
/// What. Each interior node's neighbours in its own metric (localTopology: the bubbles whose
/// bisectors bound its Voronoi cell in M_i), the defects among them (degree ≠ 6: 5 and 7 are
/// disclinations, an adjacent 5–7 pair a dislocation), and the move that removes the ones the
/// metric does not need: shakeDefects() kicks every defect node and its ring of neighbours by a
/// pseudo-random displacement of 0.3 metric units, then the dynamics relaxes them (place_nodes
/// runs a few such passes once the packing has converged, see PlacementOptions::defectPasses).
///
/// Why. On the ring disk of §4.3 74 % of the edges outside ±10 % of unit length touch a
/// defect, and the packing holds ~600 defects (14 % of its interior nodes) where the metric's
/// curvature needs ~150: mostly dislocations and 5–7 clusters trapped when the lattice grown
/// from the seed met itself. A kick of 0.3 (a third of a spacing) lets a trapped pair find its
/// partner or slip out during the relaxation; a perfect lattice around it returns to itself.
/// Measured (damping 0.33 / 0.35 / 0.37; figures in place_nodes.hpp): the ring disk's mesh has
/// 517–596 → 409–434 interior nodes of degree ≠ 6, edges within ±10 % 87.3–88.5 → 90.8–91.3 %;
/// line disk 90.3–90.5 → 92.2–92.9 %; eq. (4) 90.7–90.8 → 90.7–91.8 % (noise); steps ×1.5–2.4.
///
/// Tried and dropped (no gain beyond the ±0.5-point noise): degree-reducing edge flips realised
/// by pushing the four nodes of an edge (7-7-5-5 quadrupoles and 7-7-5-6 moves: only ~15 per
/// pass on the ring, defects 613 → 570, ±10 % +0.2 point); deleting the 7 of every 5–7 pair and
/// re-inserting a node at the largest hole of the 5 (150 moves per pass, the defect count
/// comes back to 613 after each relaxation: such a climb only moves a dislocation); kicks of
/// 0.4 melt the packing (86 %); shaking every node instead of the defects' neighbourhoods
/// gains less for more steps.
///
/// Nodes within 1.5 (metric) of the boundary are not kicked: the
/// first rows along the boundary are set by its fixed nodes, and kicking them raises the repaired
/// triangles of ex01 (eq. (4) on [−3, 3]², sharp metric corners) from 20 to 35 and lowers the
/// Fig. 16 surface's α min from 0.58 to 0.55 (docs/method.md).
///
/// Invariants: Interior nodes only, a kicked node stays inside and ≥ 0.5 (metric) from the
/// boundary; the node count is unchanged; deterministic (the kick is a hash of the node id and
/// the pass, no RNG state; the topology is computed per node), for any thread count.
#include "ablmg/mesher/bubble_system.hpp"

#include <span>
#include <vector>

namespace ablmg::mesher {

/// Voronoi neighbours of every Interior node in its own metric: the adjacency-list members
/// mapped by the Cholesky factor of M_i, the cell of the origin clipped from the square
/// [−2, 2]², neighbours in counter-clockwise order. Cell edges shorter than `minEdge` (metric)
/// are near-cocircular ties and do not count. Degree −1 (empty row) for boundary nodes and for
/// a cell that still reaches the square (a hole in the packing).
struct LocalTopology {
  std::vector<int> offsets{0};  ///< row i: ids[offsets[i] … offsets[i+1])
  std::vector<int> ids;
  std::vector<int> degree;  ///< −1 where unknown
  std::span<const int> ring(int i) const { return {ids.data() + offsets[i], ids.data() + offsets[i + 1]}; }
};

/// OpenMP over nodes; the result does not depend on the thread count. `stride` > 1: only the
/// nodes whose index is a multiple of it get a row (the others degree −1), a sample for the
/// share of defects at a stride-th of the cost.
LocalTopology localTopology(std::span<const Vec2> positions, std::span<const Metric2> metrics,
                            std::span<const NodeKind> kinds, const AdjacencyLists& adj, double minEdge = 0.05,
                            int stride = 1);

struct DefectCounts {
  long interior = 0;  ///< nodes of known degree
  long five = 0, seven = 0, other = 0;
  long total() const { return five + seven + other; }
};
DefectCounts countDefects(const LocalTopology& topo);

/// Nodes of known degree ≠ 6 and `rings` rings of their neighbours (one flag per node).
std::vector<char> defectNeighbourhood(const LocalTopology& topo, int rings);

/// Moves every flagged Interior node by `amplitude` (metric units, in M_i) in a direction
/// hashed from its id and `pass` (BubbleSystem::displace: velocity zeroed, node woken); a node
/// whose target is outside or within 0.5 of the boundary stays. Returns the nodes moved. The
/// caller refreshes the adjacency lists.
long shakeNodes(BubbleSystem& sys, const DomainGeometry& geo, std::span<const char> flagged, double amplitude,
                int pass);

}  // namespace ablmg::mesher
