#include "ablmg/fem/ordering.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <atomic>
#include <memory>

#include <amd.h>

namespace ablmg::fem {
namespace {

/// The recursion writes each piece's order into perm[offset, offset + size): the halves of a
/// cut are independent, so they run as OpenMP tasks, and the output does not depend on the
/// schedule. Membership tests use stamps: every piece takes a fresh stamp and marks its own
/// vertices; a vertex of a concurrent piece never carries ours.
struct Dissection {
  const Eigen::SparseMatrix<double>& A;
  const std::vector<Vec2>& points;
  int leafSize;
  std::vector<int> perm;
  std::unique_ptr<std::atomic<int>[]> mark;
  std::atomic<int> stamp{0};
  std::vector<int> local;  ///< index of a vertex in its leaf (valid while the leaf is ordered)

  static constexpr std::size_t kTaskCutoff = 20000;  ///< pieces smaller than this stay serial

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

  void order(std::vector<int> set, std::size_t offset) {
    if (int(set.size()) <= leafSize) {
      orderLeaf(set, offset);
      return;
    }
    Vec2 lo = points[set[0]], hi = lo;
    for (int v : set) {
      lo = lo.cwiseMin(points[v]);
      hi = hi.cwiseMax(points[v]);
    }
    const int axis = (hi.x() - lo.x()) >= (hi.y() - lo.y()) ? 0 : 1;
    if (hi[axis] == lo[axis]) {  // all points coincide: nothing to cut
      orderLeaf(set, offset);
      return;
    }
    // Median coordinate m: lower = {c < m}, middle = {c == m}, upper = {c > m}. On structured
    // grids the middle is a whole grid line, which alone separates lower from upper.
    const std::size_t half = set.size() / 2;
    std::nth_element(set.begin(), set.begin() + std::ptrdiff_t(half), set.end(),
                     [&](int a, int b) { return points[a][axis] < points[b][axis]; });
    const double m = points[set[half]][axis];
    std::vector<int> lower, middle, upper;
    for (int v : set) {
      const double c = points[v][axis];
      (c < m ? lower : c > m ? upper : middle).push_back(v);
    }
    std::vector<int>().swap(set);  // free before recursing
    // Edges lower–upper are covered by the smaller of: upper vertices touching lower, lower
    // vertices touching upper. The separator is that set plus the middle. One scan of the
    // lower side's adjacency finds both.
    const int su = newStamp();
    for (int v : upper) setMark(v, su);
    const int st = newStamp();  // upper vertices found touching lower
    std::vector<char> tl(lower.size(), 0);
    for (std::size_t k = 0; k < lower.size(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, lower[k]); it; ++it) {
        const int w = int(it.index());
        const int mw = markOf(w);
        if (mw == su || mw == st) {
          tl[k] = 1;
          setMark(w, st);
        }
      }
    std::vector<char> tu(upper.size(), 0);
    for (std::size_t k = 0; k < upper.size(); ++k) tu[k] = markOf(upper[k]) == st;
    const long cu = std::count(tu.begin(), tu.end(), 1), cl = std::count(tl.begin(), tl.end(), 1);
    std::vector<int> separator = std::move(middle);
    auto split = [&](std::vector<int>& side, const std::vector<char>& t) {
      std::vector<int> keep;
      keep.reserve(side.size());
      for (std::size_t k = 0; k < side.size(); ++k) (t[k] ? separator : keep).push_back(side[k]);
      side.swap(keep);
    };
    if (cu <= cl)
      split(upper, tu);
    else
      split(lower, tl);
    // Layout: lower, upper, separator.
    const std::size_t upperOffset = offset + lower.size(), sepOffset = upperOffset + upper.size();
    std::sort(separator.begin(), separator.end());
    emit(separator, sepOffset);
    if (lower.size() + upper.size() >= kTaskCutoff) {
#pragma omp task default(none) firstprivate(lower, offset)
      order(std::move(lower), offset);
      order(std::move(upper), upperOffset);
#pragma omp taskwait
    } else {
      order(std::move(lower), offset);
      order(std::move(upper), upperOffset);
    }
  }
};

}  // namespace

std::vector<int> geometricNestedDissection(const Eigen::SparseMatrix<double>& A, const std::vector<Vec2>& points,
                                           int leafSize) {
  const int n = int(A.rows());
  ABLMG_REQUIRE(A.cols() == n && int(points.size()) == n && A.isCompressed(),
                "geometricNestedDissection: matrix " << A.rows() << "×" << A.cols() << " (compressed: "
                                                     << A.isCompressed() << ") with " << points.size() << " points");
  Dissection d{A,
               points,
               std::max(leafSize, 1),
               std::vector<int>(n, -1),
               std::make_unique<std::atomic<int>[]>(std::size_t(n)),
               {},
               std::vector<int>(n, -1)};
  for (int v = 0; v < n; ++v) d.setMark(v, 0);
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
#pragma omp parallel if (n >= int(Dissection::kTaskCutoff))
#pragma omp single
  d.order(std::move(all), 0);
  return d.perm;
}

}  // namespace ablmg::fem
