#pragma once
/// Triangulation: an editable 2D triangulation used by the connection step (connect.hpp) as
/// the always-valid scaffold into which the ABLMG local meshes are merged (paper §4.1).
///
///   points ─ Delaunay (incremental, Hilbert order) ─ recoverEdge (boundary, then ABLMG
///   edges: Sloan's flip algorithm) ─ classify (inside/outside by the oriented boundary) ─
///   flips with a caller's criterion (eq. 12) ─ inside triangles
///
/// Validity rests on exact orientation tests only (core/predicates.hpp): every flip is done
/// on a strictly convex quadrilateral, so triangles stay counter-clockwise and conforming
/// whatever the (floating-point) flip criterion says. The Delaunay in-circle test flips only
/// when the filtered determinant is certainly positive, so insertion terminates.
/// Three artificial vertices (ids n, n+1, n+2) enclose the points; they belong to no inside
/// triangle once classify() has run.
#include "ablmg/core/vec2.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace ablmg::mesher {

class Triangulation {
 public:
  /// Delaunay triangulation of `points` (plus the three enclosing vertices). Throws
  /// InputError if two points coincide or a coordinate is not finite.
  explicit Triangulation(std::span<const Vec2> points);

  int numPoints() const { return n_; }  ///< real points (the enclosing three excluded)
  int numTriangleSlots() const { return int(tri_.size()); }
  const std::array<int, 3>& triangle(int t) const { return tri_[t]; }
  const std::array<int, 3>& neighbours(int t) const { return nbr_[t]; }  ///< across the edge opposite local vertex k
  const Vec2& point(int v) const { return p_[v]; }

  /// Triangle t and local index k such that tri[t][(k+1)%3] = a and tri[t][(k+2)%3] = b
  /// (the directed edge a→b, opposite vertex k), or t = −1.
  std::pair<int, int> findDirectedEdge(int a, int b) const;
  bool hasEdge(int a, int b) const { return findDirectedEdge(a, b).first >= 0 || findDirectedEdge(b, a).first >= 0; }

  /// Makes a–b an edge by flipping the edges crossing it (Sloan 1993), then locks it. Fails
  /// (returns false, triangulation still valid) if a vertex lies on the open segment or a
  /// locked edge crosses it.
  bool recoverEdge(int a, int b);
  bool isLocked(int a, int b) const;

  /// Marks triangles inside the domain bounded by the locked directed edges in `boundary`
  /// (domain on the left of a→b): flood fill from each side without crossing locked edges.
  /// Throws Error if a triangle is reached from both sides (the boundary is not closed).
  void classify(std::span<const std::array<int, 2>> boundary);
  bool inside(int t) const { return inside_[t] != 0; }

  /// Flips every unlocked interior edge (both triangles inside, quadrilateral strictly
  /// convex) for which `shouldFlip(x, z, y, w)` is true — x–z the current diagonal, y and w
  /// the opposite vertices — until none is left or `maxFlips` is reached. Returns the flips
  /// done; `capHit` says whether the cap stopped it.
  long flipWhile(const std::function<bool(int x, int z, int y, int w)>& shouldFlip, long maxFlips, bool& capHit);

 private:
  int n_ = 0;
  std::vector<Vec2> p_;
  std::vector<std::array<int, 3>> tri_, nbr_;
  std::vector<int> vtri_;               ///< one triangle incident to each vertex
  std::vector<std::uint8_t> lockBits_;  ///< bit k of triangle t: the edge opposite k is locked
  std::vector<char> inside_;
  int last_ = 0;  ///< walk start

  void insert(int v);
  int locate(const Vec2& q, int& onEdge) const;
  void flip(int t, int k);
  void legalize(int v, int t);
  void setNeighbour(int t, int oldN, int newN);
  void lock(int a, int b);
  bool edgeLocked(int t, int k) const { return (lockBits_[t] >> k) & 1; }
};

}  // namespace ablmg::mesher
