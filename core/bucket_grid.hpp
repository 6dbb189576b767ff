#pragma once
/// BucketGrid: a uniform grid of cells over a box, each holding a list of integer ids
/// (paper §3.3, Fig. 6: "buckets"). Used for neighbour queries among bubbles and for
/// boundary segments. Two forms:
///  - static (build once, compressed rows: ids of cell c are ids[offsets[c] .. offsets[c+1]),
///    sorted ascending inside a cell, so queries visit ids in a deterministic order);
///  - incremental (insert one id at a time; per-cell singly linked lists, newest first).
/// Units: the coordinates' own. Points outside the box are clamped to the border cells, so
/// every point has a cell; a query box is clamped the same way.
#include "ablmg/core/vec2.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace ablmg {

class BucketGrid {
 public:
  BucketGrid() = default;
  /// Grid over [lo, hi] with square cells of side ≈ cellSize (> 0); the number of cells is
  /// capped at maxCells (the cell size grows to respect the cap).
  BucketGrid(const Vec2& lo, const Vec2& hi, double cellSize, long maxCells = 1L << 24);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int numCells() const { return nx_ * ny_; }
  double cellSize() const { return cs_; }
  const Vec2& lo() const { return lo_; }
  /// Clamped in floating point before the conversion: a query far outside the grid (a wide
  /// reach box around a grid of a few close points) stays defined behaviour.
  int cellX(double x) const { return int(std::clamp(std::floor((x - lo_.x()) / cs_), 0.0, double(nx_ - 1))); }
  int cellY(double y) const { return int(std::clamp(std::floor((y - lo_.y()) / cs_), 0.0, double(ny_ - 1))); }
  int cellOf(const Vec2& p) const { return cellY(p.y()) * nx_ + cellX(p.x()); }
  Vec2 cellCentre(int c) const { return lo_ + Vec2((c % nx_ + 0.5) * cs_, (c / nx_ + 0.5) * cs_); }

  /// Static form: bucket the points (id = index), replacing any previous content.
  void build(std::span<const Vec2> points);
  /// Static form from explicit (cell, id) pairs (an id may be in several cells).
  void buildFromPairs(std::span<const std::pair<int, int>> cellIds);
  std::span<const int> cell(int c) const { return {ids_.data() + offsets_[c], ids_.data() + offsets_[c + 1]}; }

  /// Incremental form: start empty (drops static content), then insert ids one by one.
  void clearIncremental(int capacityHint = 0);
  void insert(int id, const Vec2& p);
  /// Calls f(id) for every id in cells overlapping the box [p − r, p + r] (incremental form).
  template <class F>
  void forEachIncremental(const Vec2& p, double r, F&& f) const {
    const int x0 = cellX(p.x() - r), x1 = cellX(p.x() + r), y0 = cellY(p.y() - r), y1 = cellY(p.y() + r);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int id = head_[y * nx_ + x]; id >= 0; id = next_[id]) f(id);
  }
  /// Whether pred(id) holds for some id in cells overlapping the box [p − r, p + r]
  /// (incremental form); stops at the first one.
  template <class Pred>
  bool anyIncremental(const Vec2& p, double r, Pred&& pred) const {
    return anyIncremental(p, r, r, pred);
  }
  /// The same over the box p ± (rx, ry): an anisotropic query (the bounding box of a thin
  /// metric ellipse) visits far fewer cells than the square of its long half-axis.
  template <class Pred>
  bool anyIncremental(const Vec2& p, double rx, double ry, Pred&& pred) const {
    const int x0 = cellX(p.x() - rx), x1 = cellX(p.x() + rx), y0 = cellY(p.y() - ry), y1 = cellY(p.y() + ry);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int id = head_[y * nx_ + x]; id >= 0; id = next_[id])
          if (pred(id)) return true;
    return false;
  }
  /// Calls f(id) for every id in cells overlapping the box p ± (rx, ry) (static form).
  template <class F>
  void forEachInBox(const Vec2& p, double rx, double ry, F&& f) const {
    const int x0 = cellX(p.x() - rx), x1 = cellX(p.x() + rx), y0 = cellY(p.y() - ry), y1 = cellY(p.y() + ry);
    for (int y = y0; y <= y1; ++y)
      for (int k = offsets_[y * nx_ + x0], e = offsets_[y * nx_ + x1 + 1]; k < e; ++k) f(ids_[k]);
  }
  /// Calls f(id) for every id in cells overlapping the box [p − r, p + r] (static form).
  template <class F>
  void forEach(const Vec2& p, double r, F&& f) const {
    const int x0 = cellX(p.x() - r), x1 = cellX(p.x() + r), y0 = cellY(p.y() - r), y1 = cellY(p.y() + r);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int k = offsets_[y * nx_ + x], e = offsets_[y * nx_ + x + 1]; k < e; ++k) f(ids_[k]);
  }

 private:
  Vec2 lo_{0, 0};
  double cs_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<int> offsets_{0, 0}, ids_;
  std::vector<int> head_, next_;
};

}  // namespace ablmg
