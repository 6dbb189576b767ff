#include "mesher/node_set.hpp"

#include <algorithm>

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

} // namespace ablmg::mesher
