// Test helper: the domain [0, 4]² minus the hole [1, 2]², a polygon with a hole and
// re-entrant corners (boundary tags 1 bottom, 2 right, 3 top, 4 left, 5 on the hole).
#pragma once

#include "ablmg/core/domain.hpp"

#include <utility>

namespace ablmg::test {

inline Domain squareWithHole() {
  BoundaryLoop outer = BoundaryLoop::polygon({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {1, 2, 3, 4});
  BoundaryLoop hole = BoundaryLoop::polygon({{1, 1}, {2, 1}, {2, 2}, {1, 2}}, {5, 5, 5, 5});
  return Domain(std::move(outer), {std::move(hole)});
}

}  // namespace ablmg::test
