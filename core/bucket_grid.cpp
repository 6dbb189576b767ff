#include "ablmg/core/bucket_grid.hpp"

#include "ablmg/core/error.hpp"

namespace ablmg {

BucketGrid::BucketGrid(const Vec2& lo, const Vec2& hi, double cellSize, long maxCells) : lo_(lo) {
  ABLMG_REQUIRE(cellSize > 0 && std::isfinite(cellSize), "BucketGrid: cell size must be positive, got " << cellSize);
  const double w = std::max(hi.x() - lo.x(), 0.0), h = std::max(hi.y() - lo.y(), 0.0);
  cs_ = cellSize;
  if ((w / cs_ + 1) * (h / cs_ + 1) > double(maxCells)) cs_ = std::sqrt(w * h / double(maxCells)) * 1.01 + 1e-300;
  while ((std::floor(w / cs_) + 1) * (std::floor(h / cs_) + 1) > double(maxCells)) cs_ *= 1.05;
  nx_ = int(std::floor(w / cs_)) + 1;
  ny_ = int(std::floor(h / cs_)) + 1;
  offsets_.assign(std::size_t(nx_) * ny_ + 1, 0);
}

void BucketGrid::build(std::span<const Vec2> points) {
  const int nc = numCells();
  offsets_.assign(std::size_t(nc) + 1, 0);
  std::vector<int> cellOfPoint(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cellOfPoint[i] = cellOf(points[i]);
    ++offsets_[cellOfPoint[i] + 1];
  }
  for (int c = 0; c < nc; ++c) offsets_[c + 1] += offsets_[c];
  ids_.resize(points.size());
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i) ids_[fill[cellOfPoint[i]]++] = int(i);  // ascending ids per cell
}

void BucketGrid::buildFromPairs(std::span<const std::pair<int, int>> cellIds) {
  const int nc = numCells();
  offsets_.assign(std::size_t(nc) + 1, 0);
  for (const auto& [c, id] : cellIds) ++offsets_[c + 1];
  for (int c = 0; c < nc; ++c) offsets_[c + 1] += offsets_[c];
  ids_.resize(cellIds.size());
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (const auto& [c, id] : cellIds) ids_[fill[c]++] = id;
  for (int c = 0; c < nc; ++c) std::sort(ids_.begin() + offsets_[c], ids_.begin() + offsets_[c + 1]);
}

void BucketGrid::clearIncremental(int capacityHint) {
  head_.assign(std::size_t(numCells()), -1);
  next_.clear();
  next_.reserve(std::size_t(std::max(capacityHint, 0)));
}

void BucketGrid::insert(int id, const Vec2& p) {
  if (id >= int(next_.size())) next_.resize(std::size_t(id) + 1, -1);
  const int c = cellOf(p);
  next_[id] = head_[c];
  head_[c] = id;
}

}  // namespace ablmg
