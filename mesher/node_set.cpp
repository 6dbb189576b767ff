#include "ablmg/mesher/node_set.hpp"

#include "ablmg/mesher/parallel_threshold.hpp"

#include <algorithm>
#include <utility>

namespace ablmg::mesher {

bool AdjacencyLists::isSymmetric() const {
  for (int i = 0; i < size(); ++i) {
    const auto row = neighbours(i);
    if (!std::is_sorted(row.begin(), row.end())) return false;
    for (int j : row) {
      if (j == i || j < 0 || j >= size()) return false;
      const auto back = neighbours(j);
      if (!std::binary_search(back.begin(), back.end(), i)) return false;
    }
  }
  return true;
}

void AdjacencyLists::compact() {
  if (ends.empty()) return;
  const int n = size();
  int w = 0;
  for (int i = 0; i < n; ++i) {
    const int b = offsets[i], e = ends[i];
    offsets[i] = w;
    for (int k = b; k < e; ++k) ids[w++] = ids[k];  // w ≤ k: a forward copy is safe
  }
  offsets[n] = w;
  ids.resize(std::size_t(w));
  ends.clear();
}

long coincidentNodes(const NodeSet& nodes, const AdjacencyLists& adj, std::vector<char>& drop) {
  const int n = nodes.size();
  drop.assign(std::size_t(n), 0);
  // Usually there is none: found in parallel first, the serial pass below runs only if any.
  long shared = 0;
#pragma omp parallel for schedule(static) reduction(+ : shared) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i)
    for (int j : adj.neighbours(i)) shared += j > i && nodes.positions[i] == nodes.positions[j];
  if (shared == 0) return 0;
  long count = 0;
  // Enum order is Vertex < Segment < Interior: a lower (kind, index) ranks higher.
  auto below = [&](int a, int b) { return std::pair(nodes.kinds[a], a) > std::pair(nodes.kinds[b], b); };
  for (int i = 0; i < n; ++i)
    for (int j : adj.neighbours(i)) {
      if (j <= i || nodes.positions[i] != nodes.positions[j]) continue;
      const int lower = below(i, j) ? i : j;
      count += drop[std::size_t(lower)] == 0;
      drop[std::size_t(lower)] = 1;
    }
  return count;
}

}  // namespace ablmg::mesher
