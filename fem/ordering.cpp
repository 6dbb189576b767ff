#include "ablmg/fem/ordering.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>

#include <amd.h>
#include <metis.h>
#include <omp.h>

namespace ablmg::fem {
namespace {

/// Runs body(r, begin, end) for each of the `parts` ranges of [0, n) (range r is
/// [n r / parts, n (r + 1) / parts)), on all threads of a new team when `wide`, else on the
/// calling thread (then parts must be 1). The ranges do not depend on the team, so results kept
/// per range and merged in range order are the same for any thread count. body must not throw.
template <class F>
void forRanges(std::size_t n, int parts, bool wide, F&& body) {
  if (!wide) {
    body(0, std::size_t(0), n);
    return;
  }
#pragma omp parallel
  for (int r = omp_get_thread_num(); r < parts; r += omp_get_num_threads())
    body(r, n * std::size_t(r) / std::size_t(parts), n * std::size_t(r + 1) / std::size_t(parts));
}

/// Appends each set[k] whose class c = classOf(k) is ≥ 0 to *out[c] (c < K), in set's order.
/// With `wide`, the `parts` ranges of set are classified on all threads, then written at
/// offsets counted in between: the same outputs as the serial pass, for any thread count.
template <int K, class F>
void partitionInOrder(const std::vector<int>& set, int parts, bool wide, F&& classOf,
                      const std::array<std::vector<int>*, K>& out) {
  if (!wide) {
    for (std::size_t k = 0; k < set.size(); ++k)
      if (const int c = classOf(k); c >= 0) out[std::size_t(c)]->push_back(set[k]);
    return;
  }
  std::vector<signed char> cls(set.size());
  std::vector<std::array<std::size_t, K>> at(static_cast<std::size_t>(parts));  // per range: counts, then offsets
  forRanges(set.size(), parts, true, [&](int r, std::size_t b, std::size_t e) {
    std::array<std::size_t, K> count{};
    for (std::size_t k = b; k < e; ++k) {
      cls[k] = static_cast<signed char>(classOf(k));
      if (cls[k] >= 0) ++count[std::size_t(cls[k])];
    }
    at[std::size_t(r)] = count;
  });
  for (std::size_t c = 0; c < std::size_t(K); ++c) {
    std::size_t next = out[c]->size();
    for (auto& a : at) next += std::exchange(a[c], next);
    out[c]->resize(next);
  }
  forRanges(set.size(), parts, true, [&](int r, std::size_t b, std::size_t e) {
    std::array<std::size_t, K> pos = at[std::size_t(r)];
    for (std::size_t k = b; k < e; ++k)
      if (const int c = cls[k]; c >= 0) (*out[std::size_t(c)])[pos[std::size_t(c)]++] = set[k];
  });
}

/// The recursion writes each piece's order into perm[offset, offset + size): the halves of a
/// cut are independent, so they run as OpenMP tasks, and the output does not depend on the
/// schedule. Membership tests use stamps: every piece takes a fresh stamp and marks its own
/// vertices; a vertex of a concurrent piece never carries ours.
struct Dissection {
  const Eigen::SparseMatrix<double>& A;
  const std::vector<Vec2>& points;
  int leafSize;
  int kDirections;  ///< 1: cut across the longer bounding-box axis; 4: best of x, y, x ± y
  std::vector<int> perm;
  std::unique_ptr<std::atomic<int>[]> mark;
  std::atomic<int> stamp{0};
  std::vector<int> local;  ///< index of a vertex in its leaf, or on its cut (valid while that piece is ordered)
  /// reach[4 v + d] ≥ max over v's neighbours w of |along(w, d) − along(v, d)| (rounded up to
  /// float): a vertex farther than that from a cut line has no edge across it.
  std::vector<float> reach;
  /// An exception out of a task (allocation) is kept here, rethrown after the region: the
  /// piece of the lowest offset wins (core/parallel_failure.hpp).
  ParallelFailure failure;
  TopCut top;  ///< the first cut (set by the root call only)

  static constexpr std::size_t kTaskCutoff = 20000;  ///< pieces smaller than this stay serial
  static constexpr int kQuantiles = 3;
  static constexpr double kQuantile[kQuantiles] = {0.5, 0.4, 0.6};

  int newStamp() { return stamp.fetch_add(1, std::memory_order_relaxed) + 1; }
  int markOf(int v) const { return mark[v].load(std::memory_order_relaxed); }
  void setMark(int v, int s) { mark[v].store(s, std::memory_order_relaxed); }

  void emit(const std::vector<int>& ids, std::size_t offset) {
    std::copy(ids.begin(), ids.end(), perm.begin() + std::ptrdiff_t(offset));
  }

  /// A leaf: approximate minimum degree (SuiteSparse AMD) on its own subgraph; dissection's
  /// fill is poor on small pieces, where minimum degree does better (as METIS/NESDIS do).
  void orderLeaf(std::vector<int>& set, std::size_t offset) {
    std::sort(set.begin(), set.end());
    const int n = int(set.size());
    const int s = newStamp();
    for (int k = 0; k < n; ++k) {
      setMark(set[k], s);
      local[set[k]] = k;
    }
    std::vector<int> ap(n + 1, 0), ai;
    for (int k = 0; k < n; ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, set[k]); it; ++it)
        if (markOf(int(it.index())) == s && local[it.index()] != k) ai.push_back(local[it.index()]);
      ap[k + 1] = int(ai.size());
    }
    std::vector<int> p(n);
    if (amd_order(n, ap.data(), ai.empty() ? nullptr : ai.data(), p.data(), nullptr, nullptr) != AMD_OK) {
      emit(set, offset);  // cannot happen for a valid pattern; keep id order
      return;
    }
    for (int k = 0; k < n; ++k) perm[offset + k] = set[p[k]];
  }

  /// Projection of p on cut direction d (0: x, 1: y, 2: x + y, 3: x − y; unscaled: only the
  /// order along d matters).
  static double along(const Vec2& p, int d) {
    return d == 0 ? p.x() : d == 1 ? p.y() : d == 2 ? p.x() + p.y() : p.x() - p.y();
  }
  /// The four projections of p at once (the same values as along(p, d), d = 0..3).
  static std::array<double, 4> projections(const Vec2& p) { return {p.x(), p.y(), p.x() + p.y(), p.x() - p.y()}; }

  /// Median of the piece's coordinates along d (the upper median, as a coordinate), over every
  /// vertex, or over an evenly strided sample of ≈ kMedianSample of them if `sampled` (a cut's
  /// sides then differ by a few per cent of the piece, at a fraction of the cost).
  /// 1024 rather than 4096: the quantiles' sorting was a fifth of the ordering at 10⁶ unknowns;
  /// with 1024 the ordering is 8–15 % faster and the flops no worse (bench_solve_graded: uniform
  /// 10⁵ 0.354 → 0.349 GFlop, wave front 0.946 → 0.944, layer the same, 10⁶ 13.9 → 13.3).
  static constexpr std::size_t kMedianSample = 1024;
  double medianAlong(const std::vector<int>& set, int d, bool sampled = false) const {
    const std::size_t stride = sampled ? std::max<std::size_t>(1, set.size() / kMedianSample) : 1;
    std::vector<double> c;
    c.reserve(set.size() / stride + 1);
    for (std::size_t k = 0; k < set.size(); k += stride) c.push_back(along(points[set[k]], d));
    const std::size_t half = c.size() / 2;
    std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(half), c.end());
    return c[half];
  }

  /// Sizes of the separators of the candidate cuts (cut (d, i): at m[d][i] along direction
  /// d): the middle {c = m} plus the smaller of (lower vertices touching upper) and (upper
  /// vertices touching lower), counted on the piece's own edges (stamp s marks the piece).
  /// One pass over the piece for all cuts (each vertex's point and reaches read once).
  /// With `wide`, the `parts` ranges of the piece are counted on all threads (integer sums:
  /// the same sizes).
  void separatorSizes(const std::vector<int>& set, const double (&m)[4][kQuantiles], int s, int parts, bool wide,
                      long (&size)[4][kQuantiles]) const {
    struct Counts {
      long middle[4][kQuantiles], lowerTouching[4][kQuantiles], upperTouching[4][kQuantiles];
    };
    std::vector<Counts> part(std::size_t(parts), Counts{});
    forRanges(set.size(), parts, wide, [&](int range, std::size_t b, std::size_t e) {
      countNearCuts(set.data() + b, set.data() + e, m, s, part[std::size_t(range)]);
    });
    for (std::size_t r = 1; r < part.size(); ++r)
      for (int d = 0; d < 4; ++d)
        for (int i = 0; i < kQuantiles; ++i) {
          part[0].middle[d][i] += part[r].middle[d][i];
          part[0].lowerTouching[d][i] += part[r].lowerTouching[d][i];
          part[0].upperTouching[d][i] += part[r].upperTouching[d][i];
        }
    const Counts& c = part[0];
    for (int d = 0; d < 4; ++d)
      for (int i = 0; i < kQuantiles; ++i)
        size[d][i] = c.middle[d][i] + std::min(c.lowerTouching[d][i], c.upperTouching[d][i]);
  }

  /// separatorSizes' counts over the vertices [first, last).
  template <class Counts>
  void countNearCuts(const int* first, const int* last, const double (&m)[4][kQuantiles], int s, Counts& counts) const {
    // Local counters (not through `counts`, which the atomic mark loads would make the
    // compiler reload and store around each test), added to `counts` at the end.
    long middle[4][kQuantiles] = {}, lowerTouching[4][kQuantiles] = {}, upperTouching[4][kQuantiles] = {};
    for (const int* pv = first; pv != last; ++pv) {
      const int v = *pv;
      const std::array<double, 4> c4 = projections(points[v]);
      const float* r = &reach[4 * std::size_t(v)];
      // Most vertices are farther than their reach from all twelve lines: one branch-free test
      // skips them (a vertex on a line is within its reach, which is > 0).
      bool near = false;
      for (int d = 0; d < 4; ++d)
        for (int i = 0; i < kQuantiles; ++i) near |= std::abs(c4[d] - m[d][i]) <= double(r[d]);
      if (!near) continue;
      for (int d = 0; d < 4; ++d) {
        const double c = c4[d], rd = double(r[d]);
        for (int i = 0; i < kQuantiles; ++i) {
          const double mi = m[d][i];
          if (c == mi) {
            ++middle[d][i];
            continue;
          }
          if (std::abs(c - mi) > rd) continue;
          for (Eigen::SparseMatrix<double>::InnerIterator it(A, v); it; ++it) {
            const int w = int(it.index());
            const double cw = along(points[w], d);
            if (((c < mi && cw > mi) || (c > mi && cw < mi)) && markOf(w) == s) {
              ++(c < mi ? lowerTouching[d][i] : upperTouching[d][i]);
              break;
            }
          }
        }
      }
    }
    for (int d = 0; d < 4; ++d)
      for (int i = 0; i < kQuantiles; ++i) {
        counts.middle[d][i] += middle[d][i];
        counts.lowerTouching[d][i] += lowerTouching[d][i];
        counts.upperTouching[d][i] += upperTouching[d][i];
      }
  }

  /// The piece's extent along each direction d: [lo[d], hi[d]] of along(·, d); with `wide`,
  /// over the `parts` ranges on all threads (minima and maxima: the same values).
  struct Extent {
    std::array<double, 4> lo, hi;
  };
  Extent extentOf(const std::vector<int>& set, int parts, bool wide) const {
    const std::array<double, 4> first = projections(points[set[0]]);
    std::vector<Extent> part(std::size_t(parts), Extent{first, first});
    forRanges(set.size(), parts, wide, [&](int r, std::size_t b, std::size_t e) {
      std::array<double, 4> lo = first, hi = first;  // in registers, not through the vector
      for (std::size_t k = b; k < e; ++k) {
        const std::array<double, 4> c = projections(points[set[k]]);
        for (int d = 0; d < 4; ++d) {
          lo[d] = std::min(lo[d], c[d]);
          hi[d] = std::max(hi[d], c[d]);
        }
      }
      part[std::size_t(r)] = {lo, hi};
    });
    for (const Extent& x : part)
      for (int d = 0; d < 4; ++d) {
        part[0].lo[d] = std::min(part[0].lo[d], x.lo[d]);
        part[0].hi[d] = std::max(part[0].hi[d], x.hi[d]);
      }
    return part[0];
  }

  /// The coordinates along d at the quantiles kQuantile of an evenly strided sample of
  /// ≈ kMedianSample of the piece (the 0.5 one: medianAlong's sampled median).
  void quantilesAlong(const std::vector<int>& set, int d, double (&out)[kQuantiles]) const {
    const std::size_t stride = std::max<std::size_t>(1, set.size() / kMedianSample);
    std::vector<double> c;
    c.reserve(set.size() / stride + 1);
    for (std::size_t k = 0; k < set.size(); k += stride) c.push_back(along(points[set[k]], d));
    const auto at = [&](double q) { return std::min(c.size() - 1, std::size_t(q * double(c.size()))); };
    const std::size_t mid = c.size() / 2, below = at(kQuantile[1]), above = at(kQuantile[2]);
    std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(mid), c.end());
    out[0] = c[mid];
    out[1] = out[2] = c[mid];
    if (below < mid) {  // the order statistics below the median lie in c[0, mid)
      std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(below), c.begin() + std::ptrdiff_t(mid));
      out[1] = c[below];
    }
    if (above > mid) {  // and those above it in c(mid, end)
      std::nth_element(c.begin() + std::ptrdiff_t(mid) + 1, c.begin() + std::ptrdiff_t(above), c.end());
      out[2] = c[above];
    }
  }

  struct Cut {
    int direction;
    double median;
  };

  /// The cut: of the four directions (x, y and the diagonals) and three positions along each
  /// (the median and the 0.4 and 0.6 quantiles), one with the smallest separator in the graph,
  /// give or take kNearTie; an off-centre cut's separator counts kOffCentreWeight times its
  /// size (its larger side costs more below), and the first cut (`root`) is at a median, so
  /// that the two sides, which fem/split_cholesky.hpp factorises on two threads, are even. On
  /// a graded or stretched mesh the geometrically longer axis can be the worst cut (a layer's
  /// piece is long along the layer, and a cut across it meets every one of the layer's thin
  /// rows); the separator's size is what the fill and the flops depend on. Among the cuts
  /// within kNearTie of the best, the one along whose direction the piece is longest (its
  /// extent): the pieces stay compact, and theirs are the next separators. Measured with
  /// CHOLMOD's flop counts (bench/bench_solve_graded.cpp): the off-centre positions take the
  /// uniform 317² grid from 0.62 to 0.37 GFlop and the 1001² grid from 18.0 to 14.2, the
  /// wave-front mesh 1.06 → 1.03, the layer's unchanged (0.05); positions 0.3 and 0.7 added
  /// nothing more. Exact ties: the lowest direction, then the median.
  static constexpr double kNearTie = 0.02;
  static constexpr double kOffCentreWeight = 1.1;
  Cut bestCut(const std::vector<int>& set, const Extent& ext, bool root, int parts, bool wide) {
    const int s = newStamp();
    forRanges(set.size(), parts, wide, [&](int, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) setMark(set[k], s);
    });
    const std::array<double, 4>&lo = ext.lo, &hi = ext.hi;
    double m[4][kQuantiles];
    long size[4][kQuantiles];
    for (int d = 0; d < 4; ++d) quantilesAlong(set, d, m[d]);
    separatorSizes(set, m, s, parts, wide, size);
    // Cut k = (direction k / kQuantiles, quantile k % kQuantiles).
    constexpr int K = 4 * kQuantiles;
    const auto score = [&](int k) {
      const int i = k % kQuantiles;
      return (i == 0 ? 1.0
              : root ? std::numeric_limits<double>::infinity()
                     : kOffCentreWeight) *
             double(size[k / kQuantiles][i]);
    };
    int best = 0;
    for (int k = 0; k < K; ++k)
      if (score(k) < score(best)) best = k;
    const auto extent = [&](int k) {
      const int d = k / kQuantiles;
      return (hi[d] - lo[d]) * (d < 2 ? 1.0 : std::sqrt(0.5));
    };
    int chosen = best;
    for (int k = 0; k < K; ++k)
      if (score(k) <= (1 + kNearTie) * score(best) && extent(k) > extent(chosen)) chosen = k;
    return {chosen / kQuantiles, m[chosen / kQuantiles][chosen % kQuantiles]};
  }

  /// The fewest vertices covering every edge between the two sides of a cut (König's theorem:
  /// a maximum matching of the bipartite graph of those edges, then the cover read off the
  /// alternating paths from the unmatched lower vertices). In: tl[k] = 1 for the lower
  /// vertices with an upper neighbour, tu[k] = 1 for the upper ones with a lower neighbour
  /// (those carry stamp st). Out: tl, tu flag the cover's vertices on each side, at most
  /// min(Σ tl, Σ tu) of them (taking one whole side is a cover; on a structured grid it is a
  /// minimum one already). Serial, O(cover · cut edges) at worst, deterministic.
  void minimumCover(const std::vector<int>& lower, const std::vector<int>& upper, int st, std::vector<char>& tl,
                    std::vector<char>& tu) {
    std::vector<int> left, right;  // indices into lower and upper
    for (std::size_t k = 0; k < lower.size(); ++k)
      if (tl[k]) left.push_back(int(k));
    for (std::size_t k = 0; k < upper.size(); ++k)
      if (tu[k]) {
        local[upper[k]] = int(right.size());
        right.push_back(int(k));
      }
    const int nl = int(left.size()), nr = int(right.size());
    if (nl == 0 || nr == 0) return;
    std::vector<int> start(std::size_t(nl) + 1, 0), edge;
    for (int a = 0; a < nl; ++a) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, lower[std::size_t(left[std::size_t(a)])]); it; ++it)
        if (markOf(int(it.index())) == st) edge.push_back(local[it.index()]);
      start[std::size_t(a) + 1] = int(edge.size());
    }
    // Maximum matching: greedy, then one breadth-first augmenting search per free left vertex.
    std::vector<int> mateL(std::size_t(nl), -1), mateR(std::size_t(nr), -1);
    for (int a = 0; a < nl; ++a)
      for (int e = start[a]; e < start[a + 1]; ++e)
        if (mateR[std::size_t(edge[e])] < 0) {
          mateL[std::size_t(a)] = edge[e];
          mateR[std::size_t(edge[e])] = a;
          break;
        }
    std::vector<int> from(std::size_t(nr), -1), queue;  // from[b]: the left vertex that reached b
    std::vector<int> seenR(std::size_t(nr), -1);
    for (int a0 = 0; a0 < nl; ++a0) {
      if (mateL[std::size_t(a0)] >= 0) continue;
      queue.assign(1, a0);
      int end = -1;
      for (std::size_t q = 0; q < queue.size() && end < 0; ++q) {
        const int a = queue[q];
        for (int e = start[a]; e < start[a + 1]; ++e) {
          const int b = edge[e];
          if (seenR[std::size_t(b)] == a0) continue;
          seenR[std::size_t(b)] = a0;
          from[std::size_t(b)] = a;
          if (mateR[std::size_t(b)] < 0) {
            end = b;
            break;
          }
          queue.push_back(mateR[std::size_t(b)]);
        }
      }
      for (int b = end; b >= 0;) {  // flip the path
        const int a = from[std::size_t(b)], next = mateL[std::size_t(a)];
        mateL[std::size_t(a)] = b;
        mateR[std::size_t(b)] = a;
        b = next;
      }
    }
    // König: Z = the vertices on alternating paths from the free left vertices; the cover is
    // (left ∖ Z) ∪ (right ∩ Z).
    std::vector<char> inZL(std::size_t(nl), 0), inZR(std::size_t(nr), 0);
    queue.clear();
    for (int a = 0; a < nl; ++a)
      if (mateL[std::size_t(a)] < 0) {
        inZL[std::size_t(a)] = 1;
        queue.push_back(a);
      }
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int a = queue[q];
      for (int e = start[a]; e < start[a + 1]; ++e) {
        const int b = edge[e];
        if (inZR[std::size_t(b)]) continue;
        inZR[std::size_t(b)] = 1;
        const int m = mateR[std::size_t(b)];
        if (m >= 0 && !inZL[std::size_t(m)]) {
          inZL[std::size_t(m)] = 1;
          queue.push_back(m);
        }
      }
    }
    for (int a = 0; a < nl; ++a) tl[std::size_t(left[std::size_t(a)])] = !inZL[std::size_t(a)];
    for (int b = 0; b < nr; ++b) tu[std::size_t(right[std::size_t(b)])] = inZR[std::size_t(b)];
  }

  /// Cuts `set` (more than leafSize vertices) into lower, upper and a separator, which goes
  /// into perm at its place; false (and the set ordered as a leaf) when there is nothing to cut.
  /// With `wide` (the first cut, before the recursion's tasks exist) its passes over the
  /// piece run on all threads, in `parts` fixed ranges: the same cut for any thread count.
  bool cutPiece(std::vector<int>& set, std::size_t offset, bool root, int parts, bool wide, std::vector<int>& lower,
                std::vector<int>& upper) {
    const Extent ext = extentOf(set, parts, wide);
    if (ext.lo[0] == ext.hi[0] && ext.lo[1] == ext.hi[1]) {  // all points coincide: nothing to cut
      orderLeaf(set, offset);
      return false;
    }
    // Median coordinate m: lower = {c < m}, middle = {c == m}, upper = {c > m}. On structured
    // grids the middle is a whole grid line, which alone separates lower from upper.
    Cut cut{(ext.hi[0] - ext.lo[0]) >= (ext.hi[1] - ext.lo[1]) ? 0 : 1, 0};
    if (kDirections > 1)
      cut = bestCut(set, ext, root, parts, wide);
    else
      cut.median = medianAlong(set, cut.direction);
    const int d = cut.direction;
    const double m = cut.median;
    std::vector<int> middle;
    partitionInOrder<3>(set, parts, wide,
                        [&](std::size_t k) {
                          const double c = along(points[set[k]], d);
                          return c < m ? 0 : c > m ? 2 : 1;
                        },
                        {&lower, &middle, &upper});
    if (lower.empty() && upper.empty()) {  // every point on the median line: nothing to cut
      orderLeaf(middle, offset);
      return false;
    }
    std::vector<int>().swap(set);  // free before recursing
    // The vertices on the edges lower–upper: upper vertices touching lower, lower vertices
    // touching upper; the separator is the middle plus a minimum cover of those edges
    // (minimumCover). One scan of the lower side's adjacency finds both sets; a lower vertex
    // farther below m than its reach has no neighbour above m and is skipped (the same sets:
    // only the scan is shorter). On several threads a vertex is marked st by whichever finds it
    // first: the same marks and flags.
    const int su = newStamp();
    forRanges(upper.size(), parts, wide, [&](int, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) setMark(upper[k], su);
    });
    const int st = newStamp();  // upper vertices found touching lower
    std::vector<char> tl(lower.size(), 0);
    forRanges(lower.size(), parts, wide, [&](int, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) {
        const int v = lower[k];
        if (!reach.empty() && m - along(points[v], d) > double(reach[4 * std::size_t(v) + std::size_t(d)])) continue;
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, v); it; ++it) {
          const int w = int(it.index());
          const int mw = markOf(w);
          if (mw == su || mw == st) {
            tl[k] = 1;
            setMark(w, st);
          }
        }
      }
    });
    std::vector<char> tu(upper.size(), 0);
    forRanges(upper.size(), parts, wide, [&](int, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) tu[k] = markOf(upper[k]) == st;
    });
    minimumCover(lower, upper, st, tl, tu);
    std::vector<int> separator = std::move(middle);
    auto split = [&](std::vector<int>& side, const std::vector<char>& t) {
      std::vector<int> keep;
      keep.reserve(side.size());
      partitionInOrder<2>(side, parts, wide, [&](std::size_t k) { return t[k] ? 1 : 0; }, {&keep, &separator});
      side.swap(keep);
    };
    split(upper, tu);
    split(lower, tl);
    // Layout: lower, upper, separator.
    const std::size_t sepOffset = offset + lower.size() + upper.size();
    std::sort(separator.begin(), separator.end());
    emit(separator, sepOffset);
    if (root) top = {int(lower.size()), int(upper.size())};
    return true;
  }

  /// Orders `set` into perm[offset, offset + |set|). The first call (the whole set, outside
  /// any parallel region) cuts on all threads, then opens the team whose tasks order the sides.
  void order(std::vector<int> set, std::size_t offset) {
    if (int(set.size()) <= leafSize) {
      orderLeaf(set, offset);
      return;
    }
    const bool root = offset == 0 && set.size() == perm.size();
    const bool wide = root && set.size() >= kTaskCutoff && !omp_in_parallel() && omp_get_max_threads() > 1;
    const int parts = wide ? omp_get_max_threads() : 1;
    std::vector<int> lower, upper;
    if (!cutPiece(set, offset, root, parts, wide, lower, upper)) return;
    const std::size_t upperOffset = offset + lower.size();
    if (lower.size() + upper.size() < kTaskCutoff) {
      order(std::move(lower), offset);
      order(std::move(upper), upperOffset);
    } else if (root) {
#pragma omp parallel
#pragma omp single
      orderSides(lower, upper, offset, upperOffset);
    } else {
      orderSides(lower, upper, offset, upperOffset);
    }
  }

  /// The two sides of a cut, the lower one as a task.
  void orderSides(std::vector<int>& lower, std::vector<int>& upper, std::size_t offset, std::size_t upperOffset) {
#pragma omp task default(none) firstprivate(lower, offset)
    failure.run(long(offset), [&] { order(std::move(lower), offset); });
    failure.run(long(upperOffset), [&] { order(std::move(upper), upperOffset); });
#pragma omp taskwait
  }
};

/// std::nextafter(f, +∞) for a finite f ≥ 0 (the next float up), without the libm call.
float nextUp(float f) { return std::bit_cast<float>(std::bit_cast<std::uint32_t>(f) + 1u); }

}  // namespace

std::vector<int> geometricNestedDissection(const Eigen::SparseMatrix<double>& A, const std::vector<Vec2>& points,
                                           int leafSize, CutChoice cut, TopCut* top) {
  const int n = int(A.rows());
  ABLMG_REQUIRE(A.cols() == n && int(points.size()) == n && A.isCompressed(),
                "geometricNestedDissection: matrix " << A.rows() << "×" << A.cols() << " (compressed: "
                                                     << A.isCompressed() << ") with " << points.size() << " points");
  Dissection d{A,
               points,
               std::max(leafSize, 1),
               cut == CutChoice::LongerAxis ? 1 : 4,
               std::vector<int>(n, -1),
               std::make_unique<std::atomic<int>[]>(std::size_t(n)),
               {},
               std::vector<int>(n, -1),
               {},
               {},
               {}};
  for (int v = 0; v < n; ++v) d.setMark(v, 0);
  if (cut == CutChoice::SmallestSeparator && n > d.leafSize) {  // tiny systems: one AMD leaf
    d.reach.resize(4 * std::size_t(n));
#pragma omp parallel for schedule(static) if (n >= int(Dissection::kTaskCutoff))
    for (int v = 0; v < n; ++v)
      for (int dir = 0; dir < 4; ++dir) {
        const double c = Dissection::along(points[v], dir);
        double r = 0;
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, v); it; ++it)
          r = std::max(r, std::abs(Dissection::along(points[it.index()], dir) - c));
        d.reach[4 * std::size_t(v) + std::size_t(dir)] = nextUp(float(r));
      }
  }
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  d.failure.run(-1, [&] { d.order(std::move(all), 0); });  // opens its own team (Dissection::order)
  d.failure.rethrow();
  if (top) *top = d.top;
  return d.perm;
}

std::vector<int> metisNestedDissection(const Eigen::SparseMatrix<double>& A) {
  const int n = int(A.rows());
  ABLMG_REQUIRE(A.cols() == n && A.isCompressed(), "metisNestedDissection: matrix " << A.rows() << "×" << A.cols());
  std::vector<idx_t> xadj(std::size_t(n) + 1, 0), adjncy;
  adjncy.reserve(std::size_t(A.nonZeros()));
  for (int v = 0; v < n; ++v) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, v); it; ++it)
      if (int(it.index()) != v) adjncy.push_back(idx_t(it.index()));
    xadj[std::size_t(v) + 1] = idx_t(adjncy.size());
  }
  std::vector<idx_t> perm(static_cast<std::size_t>(n)), iperm(static_cast<std::size_t>(n));
  idx_t nv = n, options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  const int status = METIS_NodeND(&nv, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data());
  ABLMG_REQUIRE(status == METIS_OK, "metisNestedDissection: METIS_NodeND failed (status " << status << ")");
  return std::vector<int>(perm.begin(), perm.end());
}

}  // namespace ablmg::fem
