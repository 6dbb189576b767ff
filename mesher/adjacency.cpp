#include "mesher/adjacency.hpp"

#include "core/bucket_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <numeric>
#include <cmath>

namespace ablmg::mesher {
namespace {

AdjacencyLists toCsr(std::vector<std::vector<int>>& rows) {
  AdjacencyLists a;
  const int n = int(rows.size());
  a.offsets.assign(std::size_t(n) + 1, 0);
  for (int i = 0; i < n; ++i) a.offsets[i + 1] = a.offsets[i] + int(rows[i].size());
  a.ids.resize(std::size_t(a.offsets[n]));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) std::copy(rows[i].begin(), rows[i].end(), a.ids.begin() + a.offsets[i]);
  return a;
}

/// CSR from a row function without per-row allocations: rows are produced in contiguous
/// blocks, one per thread, into per-thread buffers, then concatenated in row order (the result
/// does not depend on the thread count). rowFn(i, out) appends row i to out.
template <class RowFn> AdjacencyLists blockedCsr(int n, RowFn&& rowFn) {
  AdjacencyLists a;
  a.offsets.assign(std::size_t(n) + 1, 0);
  std::vector<std::vector<int>> buf(static_cast<std::size_t>(omp_get_max_threads()));
  std::vector<int> blockLo(buf.size() + 1, n);
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int lo = int(long(n) * t / nt), hi = int(long(n) * (t + 1) / nt);
    blockLo[t] = lo;
    auto& out = buf[t];
    for (int i = lo; i < hi; ++i) {
      const std::size_t before = out.size();
      rowFn(i, out);
      a.offsets[i + 1] = int(out.size() - before);
    }
  }
  for (int i = 0; i < n; ++i) a.offsets[i + 1] += a.offsets[i];
  a.ids.resize(std::size_t(a.offsets[n]));
#pragma omp parallel for schedule(static, 1)
  for (int t = 0; t < int(buf.size()); ++t)
    if (!buf[t].empty()) std::copy(buf[t].begin(), buf[t].end(), a.ids.begin() + a.offsets[blockLo[t]]);
  return a;
}

} // namespace

AdjacencyLists buildAdjacency(std::span<const Vec2> x, std::span<const Metric2> m, double radius) {
  const int n = int(x.size());
  if (n == 0) return {};
  Vec2 lo = x[0], hi = x[0];
  for (const auto& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double area = std::max((hi - lo).prod(), 1e-300);
  BucketGrid grid(lo, hi, std::max(std::sqrt(area / n), 1e-12 * (hi - lo).norm() + 1e-300), 4L * n + 16);
  grid.build(x);
  const AdjacencyLists found = blockedCsr(n, [&](int i, std::vector<int>& out) {
    // h1 (largest semi-axis of the unit ellipse) = 1/sqrt(λ_min).
    const double a = m[i].m11(), b = m[i].m12(), c = m[i].m22();
    const double lmin = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    const double R = radius * std::sqrt(2.0) / std::sqrt(std::max(lmin, 1e-300));
    const std::size_t start = out.size();
    grid.forEach(x[i], R, [&](int j) {
      if (j != i && withinMetricRadius(x[j] - x[i], m[i], m[j], radius)) out.push_back(j);
    });
    std::sort(out.begin() + std::ptrdiff_t(start), out.end());
  });
  // Transpose (counting sort: rows come out sorted), then merge each row with its transpose.
  AdjacencyLists tr;
  tr.offsets.assign(std::size_t(n) + 1, 0);
  for (int j : found.ids) ++tr.offsets[j + 1];
  for (int i = 0; i < n; ++i) tr.offsets[i + 1] += tr.offsets[i];
  tr.ids.resize(found.ids.size());
  {
    std::vector<int> fill(tr.offsets.begin(), tr.offsets.end() - 1);
    for (int i = 0; i < n; ++i)
      for (int j : found.neighbours(i)) tr.ids[fill[j]++] = i;
  }
  return blockedCsr(n, [&](int i, std::vector<int>& out) {
    const auto f = found.neighbours(i), t = tr.neighbours(i);
    std::set_union(f.begin(), f.end(), t.begin(), t.end(), std::back_inserter(out));
  });
}

AdjacencyLists refreshAdjacency(const AdjacencyLists& old, std::span<const Vec2> x, std::span<const Metric2> m,
                                double radius, std::span<const char> moved) {
  AdjacencyLists a = old;
  refreshAdjacencyInPlace(a, x, m, radius, moved);
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
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int lo = int(long(nd) * t / threads), hi = int(long(nd) * (t + 1) / threads);
    std::vector<int> stamp(lo < hi ? std::size_t(n) : 0, 0);
    auto& out = r.buf[std::size_t(t)];
    for (int k = lo; k < hi; ++k) {
      const int i = rows[std::size_t(k)];
      const int mk = i + 1;
      stamp[i] = mk;
      const std::size_t start = out.size();
      r.start[std::size_t(k)] = int(start);
      r.thread[std::size_t(k)] = t;
      const Vec2 xi = x[i];
      const Metric2& mi = m[i];
      auto test = [&](int c) {
        if (stamp[c] == mk) return;
        stamp[c] = mk;
        const Vec2 d = x[c] - xi;
        if (mi.squaredLength(d) + m[c].squaredLength(d) <= 2.0 * r2) out.push_back(c);  // withinMetricRadius
      };
      for (int j : old.neighbours(i)) {
        test(j);
        for (int c : old.neighbours(j)) test(c);
      }
      for (std::size_t q = start + 1; q < out.size(); ++q) {  // insertion sort: short, nearly sorted
        const int v = out[q];
        std::size_t b = q;
        for (; b > start && out[b - 1] > v; --b) out[b] = out[b - 1];
        out[b] = v;
      }
    }
  }
  return r;
}

/// Replaces the rows `rows[k]` (ascending) by row(k): in place when no length changes, else
/// laid out again.
template <class RowFn> void replaceRows(AdjacencyLists& lists, std::span<const int> rows, RowFn&& row) {
  const int n = lists.size(), nd = int(rows.size());
  bool sameSizes = true;
  for (int k = 0; k < nd && sameSizes; ++k) sameSizes = row(k).size() == lists.neighbours(rows[std::size_t(k)]).size();
  if (sameSizes) {
#pragma omp parallel for schedule(static)
    for (int k = 0; k < nd; ++k) {
      const auto r = row(k);
      std::copy(r.begin(), r.end(), lists.ids.begin() + lists.offsets[rows[std::size_t(k)]]);
    }
    return;
  }
  std::vector<int> slot(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < nd; ++k) slot[std::size_t(rows[std::size_t(k)])] = k;
  AdjacencyLists a;
  a.offsets.assign(std::size_t(n) + 1, 0);
  for (int i = 0; i < n; ++i)
    a.offsets[i + 1] = a.offsets[i] + int(slot[std::size_t(i)] >= 0 ? row(slot[std::size_t(i)]).size() : lists.neighbours(i).size());
  a.ids.resize(std::size_t(a.offsets[n]));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const auto r = slot[std::size_t(i)] >= 0 ? row(slot[std::size_t(i)]) : lists.neighbours(i);
    std::copy(r.begin(), r.end(), a.ids.begin() + a.offsets[i]);
  }
  lists = std::move(a);
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

} // namespace

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
  std::vector<int> dirty;
  for (int i = 0; i < n; ++i)
    if (mark[std::size_t(i)]) dirty.push_back(i);
  if (dirty.empty()) return;
  const NewRows r = twoRingRows(lists, dirty, x, m, radius);
  // Rows outside the recomputed set keep the relation symmetric: a partner gained (lost) by a
  // recomputed row gains (loses) it too.
  std::vector<std::pair<int, int>> gain, lose;  // (outside row, partner)
  for (int k = 0; k < int(dirty.size()); ++k) {
    const int a = dirty[std::size_t(k)];
    const auto nr = r.rowOf(k), orow = lists.neighbours(a);
    for (int b : nr)
      if (!mark[std::size_t(b)] && !std::binary_search(orow.begin(), orow.end(), b)) gain.push_back({b, a});
    for (int b : orow)
      if (!mark[std::size_t(b)] && !std::binary_search(nr.begin(), nr.end(), b)) lose.push_back({b, a});
  }
  std::vector<int> rows = dirty;
  std::vector<std::vector<int>> outside;
  if (!gain.empty() || !lose.empty()) {
    std::sort(gain.begin(), gain.end());
    std::sort(lose.begin(), lose.end());
    std::vector<int> touched;
    for (const auto& g : gain) touched.push_back(g.first);
    for (const auto& l : lose) touched.push_back(l.first);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (int b : touched) {
      std::vector<int> row;
      const auto o = lists.neighbours(b);
      const auto g0 = std::lower_bound(gain.begin(), gain.end(), std::pair<int, int>{b, -1});
      auto g1 = g0;
      while (g1 != gain.end() && g1->first == b) ++g1;
      const auto l0 = std::lower_bound(lose.begin(), lose.end(), std::pair<int, int>{b, -1});
      auto l1 = l0;
      while (l1 != lose.end() && l1->first == b) ++l1;
      for (int v : o) {
        bool lost = false;
        for (auto it = l0; it != l1 && !lost; ++it) lost = it->second == v;
        if (!lost) row.push_back(v);
      }
      for (auto it = g0; it != g1; ++it) row.push_back(it->second);
      std::sort(row.begin(), row.end());
      outside.push_back(std::move(row));
    }
    rows.insert(rows.end(), touched.begin(), touched.end());
  }
  // rows: dirty (ascending) then touched (ascending, disjoint from dirty); sort a permutation.
  std::vector<int> order(rows.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int p, int q) { return rows[std::size_t(p)] < rows[std::size_t(q)]; });
  std::vector<int> sortedRows(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) sortedRows[k] = rows[std::size_t(order[k])];
  const int nd = int(dirty.size());
  replaceRows(lists, sortedRows, [&](int k) -> std::span<const int> {
    const int o = order[std::size_t(k)];
    if (o < nd) return r.rowOf(o);
    return outside[std::size_t(o - nd)];
  });
}

AdjacencyLists patchAdjacency(const AdjacencyLists& old, std::span<const int> map, int firstNew,
                              std::span<const Vec2> x, std::span<const Metric2> m, double radius) {
  const int n = int(x.size());
  const int nOld = old.size();
  auto h1Of = [&](int i) {
    const double a = m[i].m11(), b = m[i].m12(), c = m[i].m22();
    const double lmin = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    return 1.0 / std::sqrt(std::max(lmin, 1e-300));
  };
  // Survivors' rows, remapped (the map is increasing, so rows stay sorted).
  std::vector<std::vector<int>> rows(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nOld; ++i) {
    const int ni = map.empty() ? i : map[i];
    if (ni < 0) continue;
    for (int j : old.neighbours(i)) {
      const int nj = map.empty() ? j : map[j];
      if (nj >= 0) rows[ni].push_back(nj);
    }
  }
  if (firstNew < n) {
    double hmax = 0;
    for (int i = 0; i < n; ++i) hmax = std::max(hmax, h1Of(i));
    Vec2 lo = x[0], hi = x[0];
    for (const auto& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    BucketGrid grid(lo, hi, std::max(std::sqrt(std::max((hi - lo).prod(), 1e-300) / n), 1e-12 * (hi - lo).norm() + 1e-300),
                    4L * n + 16);
    grid.build(x);
    const double R = radius * std::sqrt(2.0) * hmax;
    for (int k = firstNew; k < n; ++k)
      grid.forEach(x[k], R, [&](int j) {
        if (j == k || !withinMetricRadius(x[j] - x[k], m[k], m[j], radius)) return;
        rows[k].push_back(j);
        if (j < firstNew) rows[j].push_back(k);  // new ids exceed every survivor: still sorted
      });
#pragma omp parallel for schedule(static)
    for (int k = firstNew; k < n; ++k) std::sort(rows[k].begin(), rows[k].end());
  }
  return toCsr(rows);
}

} // namespace ablmg::mesher
