#pragma once
/// PointBoxTree: a static 2-d tree over a point set, for axis-aligned box queries whose cost
/// follows the local density of the points.
///
/// A bucket grid (bucket_grid.hpp) has one cell size; where the points are 10²–10⁴ times
/// denser than on average (a boundary layer's nodes under an anisotropic metric), a cell of
/// the mean spacing holds hundreds of points and every query scans them all (a
/// 2.3·10⁴-node layer: ~10³ points scanned per query, for a dozen inside the box). The tree
/// splits at the median along the longer side of each node's bounding box down to leaves of
/// at most kLeafSize points, so a query visits O(log n + points in the box) points anywhere.
/// Optional per-point scales (the half-widths of the boxes the queries around a point will
/// use) make the splits follow the queries' shape: a node is split along the side that is
/// longer in units of its points' mean scale, so where the queries are thin boxes (a layer's
/// nodes under a metric of anisotropy 10⁴: 2·10⁻⁴ by 2) the leaves are thin boxes too and a
/// query meets O(1) of them instead of O(√anisotropy) square ones.
/// Built once (O(n log n)), read-only afterwards: queries may run concurrently.
/// Units: the coordinates' own. Ids are the indices of the points given to the constructor.
#include "ablmg/core/vec2.hpp"

#include <array>
#include <limits>
#include <span>
#include <vector>

namespace ablmg {

class PointBoxTree {
 public:
  static constexpr int kLeafSize = 8;

  PointBoxTree() = default;
  /// The tree of `points` (any number, duplicates allowed; id = index), with one weight per
  /// point if `weights` is not empty (see forEachInBoxFrom), and one scale per point (both
  /// components > 0; see above) if `scales` is not empty: they shape the tree only, never
  /// what a query reports.
  explicit PointBoxTree(std::span<const Vec2> points, std::span<const double> weights = {},
                        std::span<const Vec2> scales = {});

  int size() const { return int(ids_.size()); }

  /// Calls f(id) once for every point q with |q.x − p.x| ≤ rx and |q.y − p.y| ≤ ry (closed
  /// box; rx, ry ≥ 0), in an order fixed by the tree (not ascending ids).
  template <class F>
  void forEachInBox(const Vec2& p, double rx, double ry, F&& f) const {
    forEachInBoxFrom(p, rx, ry, -std::numeric_limits<double>::infinity(), f);
  }
  /// The same for the points of weight ≥ wmin only (weights given to the constructor): a
  /// subtree whose weights are all below wmin is skipped whole, so a wide box over a dense
  /// cluster of light points costs O(log n) when they are not wanted.
  template <class F>
  void forEachInBoxFrom(const Vec2& p, double rx, double ry, double wmin, F&& f) const {
    if (nodes_.empty()) return;
    const double x0 = p.x() - rx, x1 = p.x() + rx, y0 = p.y() - ry, y1 = p.y() + ry;
    std::array<int, 64> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& nd = nodes_[std::size_t(stack[--top])];
      if (nd.wmax < wmin || nd.hi.x() < x0 || nd.lo.x() > x1 || nd.hi.y() < y0 || nd.lo.y() > y1) continue;
      const bool all = nd.lo.x() >= x0 && nd.hi.x() <= x1 && nd.lo.y() >= y0 && nd.hi.y() <= y1;
      if (all && nd.wmin >= wmin) {
        for (int k = nd.begin; k < nd.end; ++k) f(ids_[std::size_t(k)]);
      } else if (nd.left < 0) {
        for (int k = nd.begin; k < nd.end; ++k) {
          const Vec2& q = pts_[std::size_t(k)];
          if (q.x() >= x0 && q.x() <= x1 && q.y() >= y0 && q.y() <= y1 && w_[std::size_t(k)] >= wmin)
            f(ids_[std::size_t(k)]);
        }
      } else {
        stack[top++] = nd.left + 1;
        stack[top++] = nd.left;
      }
    }
  }

 private:
  /// A node covers pts_[begin, end) with bounding box [lo, hi] and weights in [wmin, wmax];
  /// inner nodes have children left and left + 1 (left < 0: a leaf).
  struct Node {
    Vec2 lo, hi;
    double wmin, wmax;
    int begin, end, left;
  };
  struct Entry {
    Vec2 p, scale;
    double w;
    int id;
  };
  void build(std::vector<Entry>& e, int begin, int end, int index, bool scaled);

  std::vector<Node> nodes_;
  std::vector<int> ids_;   ///< point ids in tree order
  std::vector<Vec2> pts_;  ///< the points in tree order (pts_[k] = points[ids_[k]])
  std::vector<double> w_;  ///< their weights (0 without weights)
};

}  // namespace ablmg
