#include "ablmg/core/point_box_tree.hpp"

#include <algorithm>

namespace ablmg {

PointBoxTree::PointBoxTree(std::span<const Vec2> points, std::span<const double> weights,
                           std::span<const Vec2> scales) {
  const int n = int(points.size());
  if (n == 0) return;
  std::vector<Entry> e(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    e[std::size_t(i)] = {points[std::size_t(i)], scales.empty() ? Vec2(1, 1) : scales[std::size_t(i)],
                         weights.empty() ? 0.0 : weights[std::size_t(i)], i};
  nodes_.reserve(std::size_t(4 * (n / kLeafSize + 1)));
  nodes_.push_back(Node{Vec2::Zero(), Vec2::Zero(), 0, 0, 0, 0, -1});
  build(e, 0, n, 0, !scales.empty());
  ids_.resize(std::size_t(n));
  pts_.resize(std::size_t(n));
  w_.resize(std::size_t(n));
  for (int k = 0; k < n; ++k) {
    ids_[std::size_t(k)] = e[std::size_t(k)].id;
    pts_[std::size_t(k)] = e[std::size_t(k)].p;
    w_[std::size_t(k)] = e[std::size_t(k)].w;
  }
}

/// Fills node `index` (already allocated) for e[begin, end): its box, and above kLeafSize
/// points the median split along the box's longer side, in units of the points' mean scale
/// if `scaled` (ties by id, so the tree is the same for any correct std::nth_element).
void PointBoxTree::build(std::vector<Entry>& e, int begin, int end, int index, bool scaled) {
  Vec2 lo = e[std::size_t(begin)].p, hi = lo, scale = Vec2::Zero();
  double wlo = e[std::size_t(begin)].w, whi = wlo;
  for (int k = begin; k < end; ++k) {
    lo = lo.cwiseMin(e[std::size_t(k)].p);
    hi = hi.cwiseMax(e[std::size_t(k)].p);
    wlo = std::min(wlo, e[std::size_t(k)].w);
    whi = std::max(whi, e[std::size_t(k)].w);
    if (scaled) scale += e[std::size_t(k)].scale;
  }
  nodes_[std::size_t(index)] = {lo, hi, wlo, whi, begin, end, -1};
  if (end - begin <= kLeafSize) return;
  // Extents compared as (hi − lo)ₓ / sₓ ≥ (hi − lo)ᵧ / sᵧ, i.e. without dividing.
  const Vec2 s = scaled ? scale : Vec2(1, 1);
  const int axis = (hi.x() - lo.x()) * s.y() >= (hi.y() - lo.y()) * s.x() ? 0 : 1;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(e.begin() + begin, e.begin() + mid, e.begin() + end, [axis](const Entry& a, const Entry& b) {
    return a.p[axis] < b.p[axis] || (a.p[axis] == b.p[axis] && a.id < b.id);
  });
  const int left = int(nodes_.size());
  nodes_.push_back(Node{Vec2::Zero(), Vec2::Zero(), 0, 0, 0, 0, -1});
  nodes_.push_back(Node{Vec2::Zero(), Vec2::Zero(), 0, 0, 0, 0, -1});
  nodes_[std::size_t(index)].left = left;
  build(e, begin, mid, left, scaled);
  build(e, mid, end, left + 1, scaled);
}

}  // namespace ablmg
