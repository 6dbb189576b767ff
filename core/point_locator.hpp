#pragma once
/// PointLocator: finds the triangle of a Mesh2 containing a point.
///
/// A uniform grid gives a start triangle near the point (a triangle whose centroid lies in
/// the point's cell, or the nearest non-empty cell); a visibility walk with exact orientation
/// tests then moves to the containing triangle. Passing the previous answer as `hint`
/// (neighbouring queries) makes the walk a few steps long. Expected O(1) per query.
/// A walk from a hint that stops at the boundary (a non-convex mesh) is redone from the grid.
/// Points outside the mesh get the triangle of the boundary edge where the walk stopped and
/// barycentric coordinates clamped to it (nearest-point extrapolation), with inside = false.
/// The mesh must outlive the locator and must be valid (Mesh2::validate).
#include "ablmg/core/mesh2.hpp"

#include <array>
#include <vector>

namespace ablmg {

class PointLocator {
 public:
  explicit PointLocator(const Mesh2& mesh);

  struct Location {
    int triangle = -1;
    std::array<double, 3> bary{};  ///< barycentric weights of the triangle's vertices, sum 1, ≥ 0
    bool inside = false;
  };
  Location locate(const Vec2& p, int hint = -1) const;

 private:
  int startTriangle(const Vec2& p) const;
  const Mesh2& mesh_;
  std::vector<std::array<int, 3>> neighbours_;
  Vec2 lo_, cellSize_;
  int nx_ = 1, ny_ = 1;
  std::vector<int> cellTriangle_;
};

}  // namespace ablmg
