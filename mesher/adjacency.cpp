#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include "ablmg/core/bucket_grid.hpp"
#include "ablmg/core/counting_sort.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/point_box_tree.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <cmath>
#include <limits>
#include <optional>

namespace ablmg::mesher {
namespace {

/// Parallel threshold for loops that recompute rows from the two-ring (~0.5 µs per row, 100×
/// a cheap per-bubble loop): the dynamics' local refreshes recompute 10²–10⁴ rows per step,
/// which kMinParallelItems left on one thread below 2048 rows.
constexpr int kMinParallelRows = 128;

/// reachBox(m, radius) widened by 10⁻⁹ of itself: a pair that passes withinMetricRadius in
/// floating point lies in one node's box even when the rounding of the box's square roots and
/// of the lengths falls the wrong way at its edge (the tree reports only points in the box).
Vec2 searchBox(const Metric2& m, double radius) { return reachBox(m, radius) * (1 + 1e-9); }

/// The nodes' search structure: a bucket grid of cells ≈ the mean spacing over the bounding
/// box, or a 2-d tree (point_box_tree.hpp) when the grid is crowded (a node shares its cell
/// with more than kCrowdedCell others on average: a boundary layer of anisotropy 10³–10⁴,
/// where each query would scan hundreds of nodes per cell). On mild metrics the grid's queries
/// are cheaper than the tree's. Both report every node in the box of weight ≥ wmin (the grid
/// also some nearby ones: callers test the metric distance). The tree's splits follow the
/// nodes' reach boxes (PointBoxTree's scales): in a layer of anisotropy 10⁴ square leaves
/// made each query visit ~10² of them, and the initial build of a layer remesh took 5 µs per
/// node.
class NodeIndex {
 public:
  static constexpr double kCrowdedCell = 16;

  NodeIndex(std::span<const Vec2> x, std::span<const double> w, std::span<const Vec2> reach) : w_(w) {
    const int n = int(x.size());
    Vec2 lo = x[0], hi = x[0];
    for (const auto& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double area = std::max((hi - lo).prod(), 1e-300);
    grid_ = BucketGrid(lo, hi, std::max(std::sqrt(area / n), 1e-12 * (hi - lo).norm() + 1e-300), 4L * n + 16);
    grid_.build(x);
    double sharing = 0;  // Σ over nodes of the size of their cell
    for (int c = 0; c < grid_.numCells(); ++c) sharing += double(grid_.cell(c).size()) * double(grid_.cell(c).size());
    if (sharing > kCrowdedCell * n) {
      grid_ = BucketGrid();
      tree_.emplace(x, w, reach);
    }
  }

  template <class F>
  void forEachInBoxFrom(const Vec2& p, double rx, double ry, double wmin, F&& f) const {
    if (tree_) {
      tree_->forEachInBoxFrom(p, rx, ry, wmin, f);
      return;
    }
    grid_.forEachInBox(p, rx, ry, [&](int j) {
      if (w_[std::size_t(j)] >= wmin) f(j);
    });
  }

 private:
  std::span<const double> w_;
  BucketGrid grid_;
  std::optional<PointBoxTree> tree_;
};

/// Each node's reach box at radius 1, and its area: the weight that decides which node of a
/// pair searches for it (the one with the smaller box; ties by the smaller id).
struct BoxWeights {
  std::vector<Vec2> reach;
  std::vector<double> w;
};

BoxWeights boxWeights(std::span<const Metric2> m) {
  BoxWeights b{std::vector<Vec2>(m.size()), std::vector<double>(m.size())};
  for (std::size_t i = 0; i < m.size(); ++i) {
    b.reach[i] = reachBox(m[i], 1.0);
    b.w[i] = b.reach[i].x() * b.reach[i].y();
  }
  return b;
}

/// A pair within the radius has |d|²_{M_i} and |d|²_{M_j} both ≤ 2·radius² (their mean is ≤
/// radius²), so it lies in the √2·radius box of either node: it is searched from one of them
/// only, the lighter (boxWeights), in a tree that skips lighter nodes whole. A coarse bubble
/// beside a boundary layer then never enumerates the layer's nodes in its wide box (a third of
/// a layer remesh's adjacency builds went there).
constexpr double kPairSearch = 1.4142135623730951;

/// CSR from a row function without per-row allocations: rows are produced in contiguous
/// blocks, one per thread, into per-thread buffers, then concatenated in row order (the result
/// does not depend on the thread count). rowFn(i, out) appends row i to out.
template <class RowFn>
AdjacencyLists blockedCsr(int n, RowFn&& rowFn) {
  AdjacencyLists a;
  a.offsets.assign(std::size_t(n) + 1, 0);
  std::vector<std::vector<int>> buf(static_cast<std::size_t>(omp_get_max_threads()));
  std::vector<int> blockLo(buf.size() + 1, n);
  ParallelFailure failure;  // rows allocate: rethrown after the region, the lowest block's
#pragma omp parallel if (n >= kMinParallelItems)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int lo = int(long(n) * t / nt), hi = int(long(n) * (t + 1) / nt);
    blockLo[t] = lo;
    auto& out = buf[t];
    failure.run(lo, [&] {
      for (int i = lo; i < hi; ++i) {
        const std::size_t before = out.size();
        rowFn(i, out);
        a.offsets[i + 1] = int(out.size() - before);
      }
    });
  }
  failure.rethrow();
  for (int i = 0; i < n; ++i) a.offsets[i + 1] += a.offsets[i];
  a.ids.resize(std::size_t(a.offsets[n]));
#pragma omp parallel for schedule(static, 1) if (n >= kMinParallelItems)
  for (int t = 0; t < int(buf.size()); ++t)
    if (!buf[t].empty()) std::copy(buf[t].begin(), buf[t].end(), a.ids.begin() + a.offsets[blockLo[t]]);
  return a;
}

/// The transpose of the compact `a` (row j lists every i whose row holds j), rows sorted: a counting sort
/// in contiguous blocks of rows per thread (core/counting_sort.hpp), so a column's rows come out
/// ascending, as from the serial sort.
AdjacencyLists transposed(const AdjacencyLists& a) {
  const int n = a.size();
  const bool parallel = n >= kMinParallelItems;
  const int threads = parallel ? omp_get_max_threads() : 1;
  std::vector<int> slot(std::size_t(threads) * std::size_t(n), 0);  // per thread and column
  AdjacencyLists tr;
  tr.offsets.assign(std::size_t(n) + 1, 0);
  tr.ids.resize(a.ids.size());
#pragma omp parallel num_threads(threads) if (parallel)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int lo = int(long(n) * t / nt), hi = int(long(n) * (t + 1) / nt);
    int* mine = slot.data() + std::size_t(t) * std::size_t(n);
    for (int i = lo; i < hi; ++i)
      for (int j : a.neighbours(i)) ++mine[j];
    countsToSlots(slot, tr.offsets);
    for (int i = lo; i < hi; ++i)
      for (int j : a.neighbours(i)) tr.ids[std::size_t(mine[j]++)] = i;
  }
  return tr;
}

}  // namespace

AdjacencyLists buildAdjacency(std::span<const Vec2> x, std::span<const Metric2> m, double radius) {
  const int n = int(x.size());
  if (n == 0) return {};
  const BoxWeights b = boxWeights(m);
  const std::vector<double>& w = b.w;
  const NodeIndex tree(x, w, b.reach);
  // Each pair once, from its lighter node (kPairSearch); the transpose below adds the other way.
  const AdjacencyLists found = blockedCsr(n, [&](int i, std::vector<int>& out) {
    const Vec2 R = searchBox(m[i], kPairSearch * radius);
    const std::size_t start = out.size();
    tree.forEachInBoxFrom(x[i], R.x(), R.y(), w[i], [&](int j) {
      if ((w[j] > w[i] || j > i) && withinMetricRadius(x[j] - x[i], m[i], m[j], radius)) out.push_back(j);
    });
    std::sort(out.begin() + std::ptrdiff_t(start), out.end());
  });
  // Transpose, then merge each row with its transpose.
  const AdjacencyLists tr = transposed(found);
  return blockedCsr(n, [&](int i, std::vector<int>& out) {
    const auto f = found.neighbours(i), t = tr.neighbours(i);
    std::set_union(f.begin(), f.end(), t.begin(), t.end(), std::back_inserter(out));
  });
}

AdjacencyLists refreshAdjacency(const AdjacencyLists& old, std::span<const Vec2> x, std::span<const Metric2> m,
                                double radius, std::span<const char> moved) {
  AdjacencyLists a = old;
  refreshAdjacencyInPlace(a, x, m, radius, moved);
  a.compact();
  return a;
}

namespace {

/// New rows of `rows` (ascending ids) from the two-ring of the current lists, in contiguous
/// blocks per thread (the result does not depend on the thread count). Candidates are
/// deduplicated with a per-thread stamp array (stamp[k] == i + 1: k already seen for row i)
/// instead of sorting the ~10× redundant two-ring; only the accepted partners (a few dozen)
/// are sorted, by insertion. Row k of the result is rowOf(k).
struct NewRows {
  std::vector<std::vector<int>> buf;
  std::vector<int> start, thread;
  std::span<const int> rowOf(int k) const {
    const auto& b = buf[std::size_t(thread[std::size_t(k)])];
    const int s = start[std::size_t(k)];
    const bool next = k + 1 < int(thread.size()) && thread[std::size_t(k + 1)] == thread[std::size_t(k)];
    return {b.data() + s, b.data() + (next ? start[std::size_t(k + 1)] : int(b.size()))};
  }
};

NewRows twoRingRows(const AdjacencyLists& old, std::span<const int> rows, std::span<const Vec2> x,
                    std::span<const Metric2> m, double radius) {
  const int n = old.size(), nd = int(rows.size());
  NewRows r;
  r.buf.resize(static_cast<std::size_t>(omp_get_max_threads()));
  r.start.assign(std::size_t(nd), 0);
  r.thread.assign(std::size_t(nd), 0);
  const double r2 = radius * radius;
  ParallelFailure failure;  // the rows allocate: rethrown after the region, the lowest block's
#pragma omp parallel if (nd >= kMinParallelRows)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int lo = int(long(nd) * t / threads), hi = int(long(nd) * (t + 1) / threads);
    failure.run(lo, [&] {
      // Candidates seen for the current row: one bit per node (n/8 bytes, cache-resident),
      // cleared after the row from the candidate list. Both passes below are branch-free
      // (append, then advance the end only if the id is new / within the radius): whether a
      // two-ring id was seen before is a coin flip that mispredicted about every other time.
      std::vector<std::uint64_t> seen(lo < hi ? std::size_t(n) / 64 + 1 : 0, 0);
      std::vector<int> cand;
      auto& out = r.buf[std::size_t(t)];
      for (int k = lo; k < hi; ++k) {
        const int i = rows[std::size_t(k)];
        const std::size_t start = out.size();
        r.start[std::size_t(k)] = int(start);
        r.thread[std::size_t(k)] = t;
        std::size_t bound = 0;
        for (int j : old.neighbours(i)) bound += 1 + old.neighbours(j).size();
        if (cand.size() < bound) cand.resize(bound);
        // 1. The distinct ids of the two-ring (i excluded), in first-visit order.
        seen[std::size_t(i) >> 6] |= std::uint64_t(1) << (i & 63);
        std::size_t nc = 0;
        auto visit = [&](int c) {
          std::uint64_t& word = seen[std::size_t(c) >> 6];
          const std::uint64_t bit = std::uint64_t(1) << (c & 63);
          cand[nc] = c;
          nc += (word & bit) == 0;
          word |= bit;
        };
        for (int j : old.neighbours(i)) {
          visit(j);
          for (int c : old.neighbours(j)) visit(c);
        }
        // 2. Those within the radius (withinMetricRadius).
        const Vec2 xi = x[i];
        const Metric2& mi = m[i];
        out.resize(start + nc);
        std::size_t kept = start;
        for (std::size_t q = 0; q < nc; ++q) {
          const int c = cand[q];
          seen[std::size_t(c) >> 6] = 0;
          const Vec2 d = x[c] - xi;
          out[kept] = c;
          kept += mi.squaredLength(d) + m[c].squaredLength(d) <= 2.0 * r2;
        }
        seen[std::size_t(i) >> 6] = 0;
        out.resize(kept);
        for (std::size_t q = start + 1; q < out.size(); ++q) {  // insertion sort: short, nearly sorted
          const int v = out[q];
          std::size_t b = q;
          for (; b > start && out[b - 1] > v; --b) out[b] = out[b - 1];
          out[b] = v;
        }
      }
    });
  }
  failure.rethrow();
  return r;
}

/// Slack given to every row when the lists are laid out again: a row may gain this many
/// partners before the next re-layout (a refresh changes a row by one or two partners). With 4,
/// the tanh layer's remesh (10⁴ of its 9.5·10⁴ bubbles refreshed every step) laid its lists
/// out again every few steps: 0.14 s of its 0.6 s of list upkeep; with 8, 0.03 s (the same
/// mesh, the 10⁶ refinement's peak unchanged).
constexpr int kRowSlack = 8;

/// Replaces the rows `rows[k]` (ascending) by row(k): in place when every new row fits in its
/// row's capacity (the usual case once the lists have slack), else all rows are laid out again
/// with kRowSlack spare entries each. O(changed entries) in the first case, O(N) in the second.
template <class RowFn>
void replaceRows(AdjacencyLists& lists, std::span<const int> rows, RowFn&& row) {
  const int n = lists.size(), nd = int(rows.size());
  bool fits = true;
  for (int k = 0; k < nd && fits; ++k) {
    const int i = rows[std::size_t(k)];
    fits = int(row(k).size()) <= lists.offsets[i + 1] - lists.offsets[i];
  }
  if (fits) {
    if (lists.ends.empty()) lists.ends.assign(lists.offsets.begin() + 1, lists.offsets.end());
#pragma omp parallel for schedule(static) if (nd >= kMinParallelItems)
    for (int k = 0; k < nd; ++k) {
      const int i = rows[std::size_t(k)];
      const auto r = row(k);
      std::copy(r.begin(), r.end(), lists.ids.begin() + lists.offsets[i]);
      lists.ends[i] = lists.offsets[i] + int(r.size());
    }
    return;
  }
  std::vector<int> slot(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < nd; ++k) slot[std::size_t(rows[std::size_t(k)])] = k;
  AdjacencyLists a;
  a.offsets.assign(std::size_t(n) + 1, 0);
  a.ends.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const int len = int(slot[std::size_t(i)] >= 0 ? row(slot[std::size_t(i)]).size() : lists.neighbours(i).size());
    a.ends[i] = a.offsets[i] + len;
    a.offsets[i + 1] = a.ends[i] + kRowSlack;
  }
  a.ids.assign(std::size_t(a.offsets[n]), -1);
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) {
    const auto r = slot[std::size_t(i)] >= 0 ? row(slot[std::size_t(i)]) : lists.neighbours(i);
    std::copy(r.begin(), r.end(), a.ids.begin() + a.offsets[i]);
  }
  lists = std::move(a);
}

/// Sorts (row, partner) pairs whose partners come in ascending order (the pairs of one centre
/// after another): a stable counting sort by row, O(pairs + n); the same order as std::sort
/// since the pairs are distinct (3·10³ pairs per step of the ring remesh).
void sortByRow(std::vector<std::pair<int, int>>& pairs, int n) {
  // Few pairs against many rows: a stable comparison sort by row gives the same order without
  // the O(n) count array.
  if (pairs.size() < std::size_t(n) / 64) {
    std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return;
  }
  std::vector<int> start(std::size_t(n) + 1, 0);
  for (const auto& p : pairs) ++start[std::size_t(p.first) + 1];
  for (int i = 0; i < n; ++i) start[std::size_t(i) + 1] += start[std::size_t(i)];
  std::vector<std::pair<int, int>> sorted(pairs.size());
  for (const auto& p : pairs) sorted[std::size_t(start[std::size_t(p.first)]++)] = p;
  pairs.swap(sorted);
}

/// Marks the nodes within two hops of the flagged ones (flags modified in place).
void growTwoHops(const AdjacencyLists& lists, std::vector<char>& flag) {
  const int n = lists.size();
  for (int hop = 0; hop < 2; ++hop) {
    std::vector<char> next(flag);
    for (int i = 0; i < n; ++i)
      if (flag[std::size_t(i)])
        for (int j : lists.neighbours(i)) next[std::size_t(j)] = 1;
    flag.swap(next);
  }
}

}  // namespace

void refreshAdjacencyInPlace(AdjacencyLists& lists, std::span<const Vec2> x, std::span<const Metric2> m, double radius,
                             std::span<const char> moved) {
  const int n = lists.size();
  // Rows to recompute, ascending: those with a moved node within two hops (all if no mask).
  std::vector<int> dirty;
  if (moved.empty()) {
    dirty.resize(std::size_t(n));
    std::iota(dirty.begin(), dirty.end(), 0);
  } else {
    std::vector<char> mark(moved.begin(), moved.end());
    growTwoHops(lists, mark);
    for (int i = 0; i < n; ++i)
      if (mark[std::size_t(i)]) dirty.push_back(i);
  }
  if (dirty.empty()) return;
  const NewRows r = twoRingRows(lists, dirty, x, m, radius);
  replaceRows(lists, dirty, [&](int k) { return r.rowOf(k); });
}

void refreshAdjacencyAround(AdjacencyLists& lists, std::span<const Vec2> x, std::span<const Metric2> m, double radius,
                            std::span<const int> centres) {
  const int n = lists.size();
  // Only the centres' rows: a pair of two other bubbles has not moved by more than their two
  // travels, which the caller keeps within the list margin; pairs with a centre are re-tested
  // here and mirrored into the partner's row below.
  std::vector<char> mark(static_cast<std::size_t>(n), 0);
  for (int c : centres) mark[std::size_t(c)] = 1;
  // The centres come ascending (a few thousand of 10⁵ rows): no scan of the marks for them.
  std::vector<int> dirty(centres.begin(), centres.end());
  if (!std::is_sorted(dirty.begin(), dirty.end())) std::sort(dirty.begin(), dirty.end());
  dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
  if (dirty.empty()) return;
  const NewRows r = twoRingRows(lists, dirty, x, m, radius);
  // Rows outside the recomputed set keep the relation symmetric: a partner gained (lost) by a
  // recomputed row gains (loses) it too. Both rows are sorted: one merge walk per row, in
  // contiguous blocks per thread (concatenated in order: independent of the thread count).
  const int nd = int(dirty.size());
  std::vector<std::vector<std::pair<int, int>>> gainOf(static_cast<std::size_t>(omp_get_max_threads())),
      loseOf(gainOf.size());
  ParallelFailure failure;  // push_back may throw: rethrown after the region, the lowest block's
#pragma omp parallel if (nd >= kMinParallelRows)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int lo = int(long(nd) * t / threads), hi = int(long(nd) * (t + 1) / threads);
    auto& gain = gainOf[std::size_t(t)];
    auto& lose = loseOf[std::size_t(t)];
    failure.run(lo, [&] {
      for (int k = lo; k < hi; ++k) {
        const int a = dirty[std::size_t(k)];
        const auto nr = r.rowOf(k), orow = lists.neighbours(a);
        std::size_t p = 0, q = 0;
        while (p < nr.size() || q < orow.size()) {
          if (q == orow.size() || (p < nr.size() && nr[p] < orow[q])) {
            if (!mark[std::size_t(nr[p])]) gain.push_back({nr[p], a});
            ++p;
          } else if (p == nr.size() || orow[q] < nr[p]) {
            if (!mark[std::size_t(orow[q])]) lose.push_back({orow[q], a});
            ++q;
          } else {
            ++p;
            ++q;
          }
        }
      }
    });
  }
  failure.rethrow();
  std::vector<std::pair<int, int>> gain, lose;  // (outside row, partner)
  for (const auto& g : gainOf) gain.insert(gain.end(), g.begin(), g.end());
  for (const auto& l : loseOf) lose.insert(lose.end(), l.begin(), l.end());
  std::vector<int> rows = dirty;
  std::vector<int> outside, outsideStart;  // new rows of the touched outside rows, back to back
  if (!gain.empty() || !lose.empty()) {
    sortByRow(gain, n);
    sortByRow(lose, n);
    std::vector<int> touched;  // outside rows with a change, ascending
    for (std::size_t g0 = 0, l0 = 0; g0 < gain.size() || l0 < lose.size();) {
      const int b =
          l0 == lose.size() || (g0 < gain.size() && gain[g0].first < lose[l0].first) ? gain[g0].first : lose[l0].first;
      std::size_t g1 = g0, l1 = l0;
      while (g1 < gain.size() && gain[g1].first == b) ++g1;
      while (l1 < lose.size() && lose[l1].first == b) ++l1;
      touched.push_back(b);
      outsideStart.push_back(int(outside.size()));
      // Merge the old row (minus the lost partners) with the gained ones; all three sorted.
      std::size_t g = g0, l = l0;
      for (int v : lists.neighbours(b)) {
        while (g != g1 && gain[g].second < v) outside.push_back(gain[g++].second);
        while (l != l1 && lose[l].second < v) ++l;
        if (l != l1 && lose[l].second == v) continue;
        outside.push_back(v);
      }
      while (g != g1) outside.push_back(gain[g++].second);
      g0 = g1;
      l0 = l1;
    }
    outsideStart.push_back(int(outside.size()));
    rows.insert(rows.end(), touched.begin(), touched.end());
  }
  // rows: dirty (ascending) then touched (ascending, disjoint from dirty): merge the two runs
  // into a permutation that sorts them.
  std::vector<int> order(rows.size());
  for (std::size_t p = 0, q = std::size_t(nd), k = 0; k < rows.size(); ++k)
    order[k] = int(q == rows.size() || (p < std::size_t(nd) && rows[p] < rows[q]) ? p++ : q++);
  std::vector<int> sortedRows(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) sortedRows[k] = rows[std::size_t(order[k])];
  replaceRows(lists, sortedRows, [&](int k) -> std::span<const int> {
    const int o = order[std::size_t(k)];
    if (o < nd) return r.rowOf(o);
    return {outside.data() + outsideStart[std::size_t(o - nd)], outside.data() + outsideStart[std::size_t(o - nd + 1)]};
  });
}

namespace {

/// The pairs within the radius that have a new bubble (id ≥ firstNew), as (row, partner) in
/// both directions, sorted, from a search structure of the new bubbles only (a population
/// pass adds 10²–10³ of them: a tree of all the bubbles each pass was a serial
/// O(n log n)). A pair within the radius lies in the kPairSearch box of either node: an old
/// bubble finds all its new partners in its own box; two new ones, from the lighter.
std::vector<std::pair<int, int>> pairsWithNew(int firstNew, std::span<const Vec2> x, std::span<const Metric2> m,
                                              double radius) {
  const int n = int(x.size());
  std::vector<std::pair<int, int>> pairs;
  if (firstNew >= n) return pairs;
  const BoxWeights b = boxWeights(m.subspan(std::size_t(firstNew)));
  const std::vector<double>& w = b.w;  // w[q]: new bubble firstNew + q
  const NodeIndex fresh(x.subspan(std::size_t(firstNew)), w, b.reach);
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<std::size_t>(omp_get_max_threads()));
  ParallelFailure failure;  // push_back may throw: rethrown after the region (index j)
#pragma omp parallel if (n >= kMinParallelItems)
  {
    auto& out = found[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (int j = 0; j < n; ++j)
      failure.run(j, [&] {
        const Vec2 R = searchBox(m[j], kPairSearch * radius);
        if (j < firstNew) {
          fresh.forEachInBoxFrom(x[j], R.x(), R.y(), -std::numeric_limits<double>::infinity(), [&](int q) {
            const int k = firstNew + q;
            if (withinMetricRadius(x[j] - x[k], m[k], m[j], radius)) out.push_back({k, j});
          });
          return;
        }
        const int p = j - firstNew;
        fresh.forEachInBoxFrom(x[j], R.x(), R.y(), w[std::size_t(p)], [&](int q) {
          const int k = firstNew + q;
          if ((w[std::size_t(q)] > w[std::size_t(p)] || q > p) && withinMetricRadius(x[k] - x[j], m[j], m[k], radius))
            out.push_back({j, k});
        });
      });
  }
  failure.rethrow();
  for (const auto& f : found)
    for (const auto& [k, j] : f) {
      pairs.push_back({k, j});
      pairs.push_back({j, k});
    }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

AdjacencyLists patchAdjacency(const AdjacencyLists& old, std::span<const int> map, int firstNew,
                              std::span<const Vec2> x, std::span<const Metric2> m, double radius) {
  const int n = int(x.size());
  const int nOld = old.size();
  // Local reaches (pairsWithNew): a fine bubble never scans the box a coarse one needs (a
  // global max h1 made graded remeshes scan ~10⁴ nodes per insertion).
  const std::vector<std::pair<int, int>> pairs = pairsWithNew(firstNew, x, m, radius);
  // Rows: survivors' remapped rows (the map is increasing, so they stay sorted) followed by
  // their new partners (ids ≥ firstNew, above every survivor), then the new rows.
  std::vector<int> rowOfOld(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < nOld; ++i) {
    const int ni = map.empty() ? i : map[i];
    if (ni >= 0) rowOfOld[std::size_t(ni)] = i;
  }
  AdjacencyLists a;
  a.offsets.assign(std::size_t(n) + 1, 0);
  {
    std::vector<int> extra(static_cast<std::size_t>(n) + 1, 0);
    for (const auto& pr : pairs) ++extra[std::size_t(pr.first)];
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
    for (int i = 0; i < n; ++i) {
      int c = extra[std::size_t(i)];
      const int o = rowOfOld[std::size_t(i)];
      if (o >= 0)
        for (int j : old.neighbours(o)) c += (map.empty() ? j : map[j]) >= 0;
      a.offsets[i + 1] = c;
    }
  }
  for (int i = 0; i < n; ++i) a.offsets[i + 1] += a.offsets[i];
  a.ids.resize(std::size_t(a.offsets[n]));
  std::vector<int> pairStart(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& pr : pairs) ++pairStart[std::size_t(pr.first) + 1];
  for (int i = 0; i < n; ++i) pairStart[i + 1] += pairStart[i];
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) {
    int w = a.offsets[i];
    const int o = rowOfOld[std::size_t(i)];
    if (o >= 0)
      for (int j : old.neighbours(o)) {
        const int nj = map.empty() ? j : map[j];
        if (nj >= 0) a.ids[std::size_t(w++)] = nj;
      }
    for (int p = pairStart[i]; p < pairStart[i + 1]; ++p) a.ids[std::size_t(w++)] = pairs[std::size_t(p)].second;
  }
  return a;
}

}  // namespace ablmg::mesher
