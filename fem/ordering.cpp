#include "fem/ordering.hpp"

#include "core/error.hpp"

#include <algorithm>

#include <amd.h>

namespace ablmg::fem {
namespace {

struct Dissection {
  const Eigen::SparseMatrix<double>& A;
  const std::vector<Vec2>& points;
  int leafSize;
  std::vector<int> perm;
  std::vector<int> mark;  ///< mark[v] = stamp of the lower half v currently belongs to
  int stamp = 0;

  std::vector<int> local;  ///< local[v] = index of v in the current leaf, −1 elsewhere

  /// A leaf: approximate minimum degree (SuiteSparse AMD) on its own subgraph; ND's fill is
  /// poor on small pieces, where minimum degree does better (as METIS/NESDIS do).
  void orderLeaf(std::vector<int>& set) {
    std::sort(set.begin(), set.end());
    const int n = int(set.size());
    for (int k = 0; k < n; ++k) local[set[k]] = k;
    std::vector<int> ap(n + 1, 0), ai;
    for (int k = 0; k < n; ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, set[k]); it; ++it) {
        const int l = local[it.index()];
        if (l >= 0 && l != k) ai.push_back(l);
      }
      ap[k + 1] = int(ai.size());
    }
    std::vector<int> p(n);
    const int status = amd_order(n, ap.data(), ai.empty() ? nullptr : ai.data(), p.data(), nullptr, nullptr);
    for (int k = 0; k < n; ++k) local[set[k]] = -1;
    if (status != AMD_OK) {  // cannot happen for a valid pattern; keep id order
      perm.insert(perm.end(), set.begin(), set.end());
      return;
    }
    for (int k = 0; k < n; ++k) perm.push_back(set[p[k]]);
  }

  void order(std::vector<int>& set) {
    if (int(set.size()) <= leafSize) {
      orderLeaf(set);
      return;
    }
    Vec2 lo = points[set[0]], hi = lo;
    for (int v : set) {
      lo = lo.cwiseMin(points[v]);
      hi = hi.cwiseMax(points[v]);
    }
    const int axis = (hi.x() - lo.x()) >= (hi.y() - lo.y()) ? 0 : 1;
    if (hi[axis] == lo[axis]) {  // all points coincide: nothing to cut
      std::sort(set.begin(), set.end());
      perm.insert(perm.end(), set.begin(), set.end());
      return;
    }
    // Median coordinate m: lower = {c < m}, middle = {c == m}, upper = {c > m}. On structured
    // grids the middle is a whole grid line, which alone separates lower from upper.
    const std::size_t half = set.size() / 2;
    std::nth_element(set.begin(), set.begin() + half, set.end(),
                     [&](int a, int b) { return points[a][axis] < points[b][axis]; });
    const double m = points[set[half]][axis];
    std::vector<int> lower, middle, upper;
    for (int v : set) {
      const double c = points[v][axis];
      (c < m ? lower : c > m ? upper : middle).push_back(v);
    }
    // Edges lower–upper are covered by the smaller of: upper vertices touching lower, lower
    // vertices touching upper. The separator is that set plus the middle.
    // One scan of the lower side's adjacency finds both sets.
    const int su = ++stamp;
    for (int v : upper) mark[v] = su;
    const int st = ++stamp;  // upper vertices found touching lower
    std::vector<char> tl(lower.size(), 0);
    for (std::size_t k = 0; k < lower.size(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, lower[k]); it; ++it)
        if (mark[it.index()] == su || mark[it.index()] == st) {
          tl[k] = 1;
          mark[it.index()] = st;
        }
    std::vector<char> tu(upper.size(), 0);
    for (std::size_t k = 0; k < upper.size(); ++k) tu[k] = mark[upper[k]] == st;
    const long cu = std::count(tu.begin(), tu.end(), 1), cl = std::count(tl.begin(), tl.end(), 1);
    std::vector<int> separator = middle;
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
    std::vector<int>().swap(set);  // free before recursing
    order(lower);
    order(upper);
    std::sort(separator.begin(), separator.end());
    perm.insert(perm.end(), separator.begin(), separator.end());
  }
};

} // namespace

std::vector<int> geometricNestedDissection(const Eigen::SparseMatrix<double>& A, const std::vector<Vec2>& points,
                                           int leafSize) {
  const int n = int(A.rows());
  ABLMG_REQUIRE(A.cols() == n && int(points.size()) == n && A.isCompressed(),
                "geometricNestedDissection: matrix " << A.rows() << "×" << A.cols() << " (compressed: "
                                                     << A.isCompressed() << ") with " << points.size() << " points");
  Dissection d{A, points, std::max(leafSize, 1), {}, std::vector<int>(n, 0), 0, std::vector<int>(n, -1)};
  d.perm.reserve(n);
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  d.order(all);
  return d.perm;
}

} // namespace ablmg::fem
