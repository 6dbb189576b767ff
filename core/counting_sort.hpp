#pragma once
/// The shared middle step of the parallel, stable counting sorts (BucketGrid::build, Mesh2's
/// half-edges, the adjacency lists' transpose): each thread counts the items of its contiguous
/// block per bucket, this step turns the counts into bucket offsets and into each thread's first
/// position in every bucket, and each thread then fills its positions. The blocks fill a bucket in
/// thread order, so every bucket lists its items in block order: the serial sort's result,
/// whatever the number of threads.
#include <cstddef>
#include <span>

namespace ablmg {

/// Called by every thread of an OpenMP team (or outside one, by the one thread), once thread t
/// has counted its block's items of bucket b into slot[t · B + b] (B = offsets.size() − 1;
/// slot.size() = B × the threads asked for, the rows of threads the team did not get left 0).
/// Sets offsets[b + 1] = offsets[b] + Σ_t count(t, b), offsets[0] as given, and turns each
/// count into thread t's first position in bucket b. Synchronises the team before and after.
inline void countsToSlots(std::span<int> slot, std::span<int> offsets) {
  const std::size_t buckets = offsets.size() - 1, threads = buckets > 0 ? slot.size() / buckets : 0;
#pragma omp barrier
#pragma omp single
  for (std::size_t b = 0; b < buckets; ++b) {
    int n = 0;
    for (std::size_t t = 0; t < threads; ++t) n += slot[t * buckets + b];
    offsets[b + 1] = offsets[b] + n;
  }
#pragma omp for schedule(static)
  for (long b = 0; b < long(buckets); ++b) {
    int next = offsets[std::size_t(b)];
    for (std::size_t t = 0; t < threads; ++t) {
      int& s = slot[t * buckets + std::size_t(b)];
      const int n = s;
      s = next;
      next += n;
    }
  }
}

}  // namespace ablmg
