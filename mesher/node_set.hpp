#pragma once
/// The output of node placement (paper §3) and input of the connection (paper §4).
///
/// NodeSet: node positions (structure of arrays) with the geometric entity each node lives on
/// (paper §3.1: vertices, edges, faces). AdjacencyLists: CSR lists of neighbours within the
/// adjacency radius (1.7σ in the metric sense, §3.3).
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace ablmg::mesher {

enum class NodeKind : std::uint8_t {
  Vertex,   ///< a corner of the PSLG: fixed
  Segment,  ///< on a boundary loop between corners: slides along it
  Interior  ///< inside the domain: moves freely, never leaves it
};

struct NodeSet {
  std::vector<Vec2> positions;
  std::vector<NodeKind> kinds;
  std::vector<int> loops;   ///< boundary loop index for Vertex/Segment nodes, −1 for Interior
  std::vector<double> arc;  ///< for boundary nodes: position along its loop as a point index + fraction
                            ///< (segment k at fraction t ↦ k + t), −1 for Interior
  int size() const { return int(positions.size()); }
};

/// Symmetric neighbour lists in compressed rows: neighbours of i are ids[offsets[i] .. end(i)),
/// end(i) = offsets[i+1] when `ends` is empty (compact form, what every public function returns
/// unless it says otherwise), else ends[i] ≤ offsets[i+1]: rows with slack, so that the
/// dynamics' local refreshes rewrite a row in place instead of laying out all rows again.
/// Invariants: symmetric (j ∈ adj(i) ⇔ i ∈ adj(j)); each row sorted by id; no self-loops.
struct AdjacencyLists {
  std::vector<int> offsets{0};
  std::vector<int> ids;
  std::vector<int> ends;  ///< empty (compact) or one row end per node
  int size() const { return int(offsets.size()) - 1; }
  std::span<const int> neighbours(int i) const {
    return {ids.data() + offsets[i], ids.data() + (ends.empty() ? offsets[i + 1] : ends[i])};
  }
  bool isSymmetric() const;
  /// Drops the slack: afterwards `ends` is empty and ids holds the rows back to back.
  void compact();
};

/// The nodes to drop so that no two share a point (exact coordinate equality): of each pair
/// of coincident nodes the one of lower rank is marked, Interior below Segment below Vertex,
/// and of equal kinds the higher index; so of every group exactly its top node stays and a
/// boundary node is never dropped for an interior one. Pairs are read from `adj`, which must
/// hold every pair within its radius at the current positions (a coincident pair is at metric
/// distance 0). Returns the number marked (0: `drop` is all zero). Deterministic, O(Σ rows).
long coincidentNodes(const NodeSet& nodes, const AdjacencyLists& adj, std::vector<char>& drop);

}  // namespace ablmg::mesher
