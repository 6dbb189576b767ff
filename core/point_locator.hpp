#pragma once
/// PointLocator: finds the triangle of a Mesh2 containing a point.
///
/// A uniform grid (about one cell per two triangles) buckets the triangles by centroid. The
/// start triangle is, in the point's cell (or the nearest non-empty one), its lowest triangle
/// id if it holds at most 8; a crowded cell's triangles form a small k-d tree (leaves of ≤ 8,
/// split at the median of the wider side), and the start is the triangle of the point's leaf
/// whose centroid is nearest. The trees follow the triangles'
/// density and shape, so on a graded, stretched mesh (an adapted boundary layer, anisotropy
/// 10³–10⁴) the start is a few triangles away, where the first triangle of a cell could be
/// thousands of thin triangles from the point (tanh-layer cycle mesh: 2× less CPU per query
/// without a hint); a uniform mesh's cells hold a triangle or two and cost as before. A visibility walk with exact orientation tests then moves
/// to the containing triangle. Passing the previous answer as `hint`
/// (neighbouring queries) makes the walk a few steps long. Expected O(1) per query. A walk from a
/// hint gives up after 4√n + 64 steps; one from the grid goes on for up to n steps (across a
/// stretched layer it can be 10³–10⁴ thin triangles long), and only then (a cycle) the
/// triangles are scanned.
/// A walk from a hint that stops at the boundary (a non-convex mesh) is redone from the grid. A
/// walk from the grid that stops there too (its straight line left the mesh through a notch: the
/// start triangle of a cell straddling a re-entrant corner lies across it) is checked against
/// the triangles of the 3 × 3 cells around p and redone from a few of them, so a point inside is
/// found inside whatever the triangle order. Points outside the mesh get the boundary triangle,
/// among those walks' stops, whose clamped point is nearest, and barycentric coordinates clamped
/// to it (nearest-point extrapolation), with inside = false.
/// The mesh must outlive the locator and must be valid (Mesh2::validate).
#include "ablmg/core/mesh2.hpp"

#include <array>
#include <vector>

namespace ablmg {

/// neighbours[t][k] = the triangle across the edge opposite vertex k of t, −1 on the boundary.
/// On a valid mesh (consistently oriented, manifold) this is Mesh2::triangleNeighbours, in a
/// third of its time (O(n)).
std::vector<std::array<int, 3>> neighboursOf(const Mesh2& mesh);

class PointLocator {
 public:
  explicit PointLocator(const Mesh2& mesh);

  struct Location {
    int triangle = -1;
    std::array<double, 3> bary{};  ///< barycentric weights of the triangle's vertices, sum 1, ≥ 0
    bool inside = false;
  };
  Location locate(const Vec2& p, int hint = -1) const;
  /// A start for locating p: `previous` (≥ 0: a hint, or the triangle of a query made just
  /// before, e.g. a neighbouring point of a batch) if p is in it; else the grid's start
  /// triangle, or `previous` if p lies fewer of its own heights outside it (−min barycentric weight: an affine-invariant distance, so on a
  /// stretched mesh a thin triangle next to p beats a centroid close to p in Euclidean terms).
  /// In a batch of points in no spatial order, the previous answer alone can be the whole mesh
  /// away; the grid's start alone is tens to hundreds of thin triangles from p on an
  /// anisotropic layer (tanh-layer cycle mesh: 212 walk steps per query from it).
  int startNear(const Vec2& p, int previous) const;
  /// Per triangle t and local edge k (opposite vertex k): the neighbour triangle or −1, as
  /// Mesh2::triangleNeighbours (the walk's adjacency, for callers that need it too).
  const std::vector<std::array<int, 3>>& neighbours() const { return neighbours_; }

 private:
  int startTriangle(const Vec2& p) const;
  double outside(int t, const Vec2& p) const;  ///< −min barycentric weight of p in t (≤ 0 inside)
  /// Visibility walk from t towards p: the triangle holding p, or the one whose boundary edge p
  /// lies beyond (atBoundary), or −1 after `cap` steps (a cycle).
  int walk(int t, const Vec2& p, int cap, bool& atBoundary) const;
  bool contains(int t, const Vec2& p) const;                ///< exact orientation tests
  Location clamped(int t, const Vec2& p) const;             ///< barycentrics clamped to t
  Vec2 clampedPoint(const Location& loc) const;             ///< the point they weight
  int acrossTheBoundary(const Vec2& p, int stopped) const;  ///< walks that stopped at the boundary
  int build(int lo, int hi);                                ///< k-d tree of order_[lo, hi); returns its root
  int nearestInTree(int root, const Vec2& p) const;         ///< the start triangle from one cell's tree
  const Mesh2& mesh_;
  std::vector<std::array<int, 3>> neighbours_;
  /// k-d tree node: an inner node splits at `split` along `axis` (children left, right); a
  /// leaf (axis < 0) holds order_[lo, hi).
  struct Node {
    double split = 0;
    int axis = -1, left = -1, right = -1, lo = 0, hi = 0;
  };
  std::vector<Node> nodes_;
  std::vector<int> order_;      ///< triangle ids, grouped by cell, then by leaf
  std::vector<Vec2> centroid_;  ///< per triangle
  Vec2 lo_, cellSize_;
  int nx_ = 1, ny_ = 1;
  std::vector<int> cellStart_;  ///< cell c's triangles are order_[cellStart_[c], cellStart_[c + 1])
  std::vector<int> cellNode_;   ///< per cell: start triangle (≥ 0), tree root r as −2 − r, −1 if empty
};

}  // namespace ablmg
