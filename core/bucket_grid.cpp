#include "ablmg/core/bucket_grid.hpp"

#include "ablmg/core/counting_sort.hpp"
#include "ablmg/core/error.hpp"

#include <omp.h>

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
  const int nc = numCells(), n = int(points.size());
  offsets_.assign(std::size_t(nc) + 1, 0);
  ids_.resize(points.size());
  // A counting sort in contiguous blocks of points per thread (core/counting_sort.hpp): every
  // cell lists its ids ascending, as the serial sort does.
  constexpr int kParallelPoints = 1 << 15;
  const bool parallel = n >= kParallelPoints;
  const int threads = parallel ? omp_get_max_threads() : 1;
  std::vector<int> cellOfPoint(points.size());
  std::vector<int> slot(std::size_t(threads) * std::size_t(nc), 0);  // per thread and cell
#pragma omp parallel num_threads(threads) if (parallel)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int lo = int(long(n) * t / nt), hi = int(long(n) * (t + 1) / nt);
    int* mine = slot.data() + std::size_t(t) * std::size_t(nc);
    for (int i = lo; i < hi; ++i) ++mine[cellOfPoint[std::size_t(i)] = cellOf(points[std::size_t(i)])];
    countsToSlots(slot, offsets_);
    for (int i = lo; i < hi; ++i) ids_[std::size_t(mine[cellOfPoint[std::size_t(i)]]++)] = i;
  }
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
