#pragma once
/// Domain: a planar straight-line graph (PSLG) made of closed boundary loops (paper §3.1).
///
/// The outer loop is counter-clockwise and holes are clockwise (the constructor reorients
/// loops given the other way). Segment k of a loop joins points[k] to points[(k+1) % n] and
/// carries the integer reference tag tags[k] (kept on the output's boundary edges).
///
/// A loop may be `smooth`: its points then sample a smooth curve (a circle given as a
/// polygon of many points), and only its `corners` (points where the tag changes or the
/// boundary turns by more than 30°, and the fixedPoints and ends of keptSegments) are fixed
/// mesh vertices; the mesher places its own boundary nodes along the polyline. Otherwise every
/// point is a corner and a mesh vertex.
/// Slits (cracks): a loop may run along a polyline and back, a zero-width gap. Its points then
/// repeat (the two lips have distinct points at the same coordinates) and segment k is the
/// reverse of another: a slit attached to the boundary is such a detour of the outer loop (or a
/// hole's), a free slit a hole loop of zero area that runs along the crack and back. Both lips
/// are boundary with their own tags, the slit's end inside the domain (the tip) is a corner.
/// withSlit() builds them; meshDomain (mesher/mesher.hpp) meshes them with distinct vertices on
/// the two lips.
/// Units: the coordinates' own.
#include "ablmg/core/vec2.hpp"

#include <string>
#include <utility>
#include <vector>

namespace ablmg {

struct BoundaryLoop {
  std::vector<Vec2> points;
  std::vector<int> tags;  ///< one per segment; empty = all 1
  bool smooth = false;
  /// Per point (empty = none): a corner whatever the turn (a required vertex, a junction of
  /// subdomain interfaces). Always a mesh vertex at exactly this position.
  std::vector<char> fixedPoints;
  /// Per segment (empty = none): kept as one mesh edge, its end points corners, no node placed
  /// inside it (a required edge, a piece of an interface discretized for both its sides).
  std::vector<char> keptSegments;

  /// A polygonal loop (not smooth, no fixed points, no kept segments); empty tags = all 1.
  static BoundaryLoop polygon(std::vector<Vec2> points, std::vector<int> tags = {}) {
    BoundaryLoop loop;
    loop.points = std::move(points);
    loop.tags = std::move(tags);
    return loop;
  }
};

class Domain {
 public:
  Domain() = default;
  /// Builds and validates (see validate()). Throws InputError naming the bad loop/segment.
  Domain(BoundaryLoop outer, std::vector<BoundaryLoop> holes = {});

  /// Rectangle [x0,x1]×[y0,y1], tags 1 (bottom), 2 (right), 3 (top), 4 (left).
  static Domain rectangle(double x0, double y0, double x1, double y1);
  /// Disk sampled by `samples` points on a smooth loop, tag 1.
  static Domain disk(Vec2 centre, double radius, int samples = 2048);

  const BoundaryLoop& outer() const { return loops_.front(); }
  /// All loops: [0] is the outer loop, then the holes.
  const std::vector<BoundaryLoop>& loops() const { return loops_; }

  /// Area enclosed (outer minus holes), exact up to round-off for the polygon.
  double area() const;
  /// Bounding box of the outer loop: {min, max}.
  std::pair<Vec2, Vec2> boundingBox() const;
  /// Point-in-domain test (strictly inside the outer loop and outside every hole; points on
  /// the boundary count as inside). Uses robust orientation.
  bool contains(const Vec2& p) const;
  /// Euclidean distance from p to the nearest boundary segment.
  double distanceToBoundary(const Vec2& p) const;
  /// Index lists of the corner points of loop l (all points unless the loop is smooth).
  std::vector<int> corners(int l) const;

  /// This domain with a slit along `points` (≥ 2, distinct, every segment inside the domain):
  /// when points[0] is on a loop (a point of it, or inside one of its segments, which is then
  /// split there) the slit is attached there and points.back() is its tip; otherwise it is free
  /// (a new hole loop of zero area, both ends tips). The lip on the left of points[0] →
  /// points.back() gets tag `tagLeft`, the other `tagRight`. Throws InputError naming the point
  /// for a slit that leaves the domain, crosses the boundary or another slit, or ends on it.
  Domain withSlit(const std::vector<Vec2>& points, int tagLeft, int tagRight) const;
  /// True when a loop has a zero-width gap (a slit).
  bool hasSlits() const;

  /// Rejects: loops with < 3 points, non-finite coordinates, zero-length segments, duplicate
  /// points, self-intersections or intersections between loops, holes outside the outer loop,
  /// tag vectors of the wrong size. The message names loop and segment index. Allowed: the
  /// zero-width gaps of slits (a segment whose exact reverse is in the same loop; segments of
  /// one loop that meet only at a point the loop visits twice).
  void validate() const;

 private:
  std::vector<BoundaryLoop> loops_;
};

}  // namespace ablmg
