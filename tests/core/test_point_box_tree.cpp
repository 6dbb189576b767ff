#include "ablmg/core/point_box_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace ablmg;

namespace {

/// Ids the tree reports for the box p ± (rx, ry), sorted, with duplicates kept.
std::vector<int> query(const PointBoxTree& t, const Vec2& p, double rx, double ry) {
  std::vector<int> ids;
  t.forEachInBox(p, rx, ry, [&](int id) { ids.push_back(id); });
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<int> bruteForce(const std::vector<Vec2>& pts, const Vec2& p, double rx, double ry) {
  std::vector<int> ids;
  for (int i = 0; i < int(pts.size()); ++i)
    if (std::abs(pts[std::size_t(i)].x() - p.x()) <= rx && std::abs(pts[std::size_t(i)].y() - p.y()) <= ry)
      ids.push_back(i);
  return ids;
}

}  // namespace

// A layer: most points in a band 10⁴ times thinner than it is long, the rest spread over the
// square, plus duplicates; thin and wide boxes, some on points, some outside the set.
TEST(PointBoxTree, BoxQueriesReportEveryPointInsideOnceAndNoOther) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> pts;
  for (int i = 0; i < 3000; ++i) pts.emplace_back(u(rng), 0.5 + 1e-4 * (u(rng) - 0.5));
  for (int i = 0; i < 1000; ++i) pts.emplace_back(u(rng), u(rng));
  for (int i = 0; i < 50; ++i) pts.push_back(pts[std::size_t(i * 7)]);
  pts.emplace_back(0.25, 0.5);  // exactly on the edge of a query box below
  const PointBoxTree tree(pts);
  EXPECT_EQ(tree.size(), int(pts.size()));
  for (int q = 0; q < 400; ++q) {
    const Vec2 p = q % 2 ? pts[std::size_t(q * 9)] : Vec2(1.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2);
    const double rx = q % 3 == 0 ? 0.2 * u(rng) : 1e-3 * u(rng), ry = q % 5 == 0 ? 0.3 * u(rng) : 3e-5 * u(rng);
    EXPECT_EQ(query(tree, p, rx, ry), bruteForce(pts, p, rx, ry)) << "query " << q;
  }
  EXPECT_EQ(query(tree, Vec2(0.2, 0.5), 0.05, 0.0), bruteForce(pts, Vec2(0.2, 0.5), 0.05, 0.0));
  EXPECT_FALSE(query(tree, Vec2(0.2, 0.5), 0.05, 0.0).empty());
  EXPECT_EQ(query(tree, Vec2(0.5, 0.5), 10, 10).size(), pts.size());
}

// Scales shape the splits only: the layer's points with thin scales (the band's queries) and
// square ones elsewhere report exactly what the unscaled tree does.
TEST(PointBoxTree, ScaledSplitsReportTheSamePoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> pts, scales;
  for (int i = 0; i < 3000; ++i) {
    pts.emplace_back(u(rng), 0.5 + 1e-4 * (u(rng) - 0.5));
    scales.emplace_back(1e-2, 1e-6);
  }
  for (int i = 0; i < 1000; ++i) {
    pts.emplace_back(u(rng), u(rng));
    scales.emplace_back(1e-2, 1e-2);
  }
  for (int i = 0; i < 20; ++i) {  // duplicates, and scales 10³⁰⁰ apart
    pts.push_back(pts[std::size_t(i * 11)]);
    scales.emplace_back(1e-150, 1e150);
  }
  const PointBoxTree plain(pts), scaled(pts, {}, scales);
  EXPECT_EQ(scaled.size(), int(pts.size()));
  for (int q = 0; q < 400; ++q) {
    const Vec2 p = q % 2 ? pts[std::size_t(q * 9)] : Vec2(1.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2);
    const double rx = q % 3 == 0 ? 0.2 * u(rng) : 2e-2 * u(rng), ry = q % 5 == 0 ? 0.3 * u(rng) : 2e-6 * u(rng);
    const std::vector<int> want = bruteForce(pts, p, rx, ry);
    EXPECT_EQ(query(scaled, p, rx, ry), want) << "query " << q;
    EXPECT_EQ(query(plain, p, rx, ry), want) << "query " << q;
  }
}

TEST(PointBoxTree, EmptyAndTinySets) {
  const PointBoxTree none(std::vector<Vec2>{});
  EXPECT_TRUE(query(none, Vec2(0, 0), 1, 1).empty());
  const std::vector<Vec2> one{Vec2(1, 2)};
  const PointBoxTree single(one);
  EXPECT_EQ(query(single, Vec2(1, 2), 0, 0), std::vector<int>{0});
  EXPECT_TRUE(query(single, Vec2(1.1, 2), 0.05, 1).empty());
  const std::vector<Vec2> same(100, Vec2(3, 3));  // one point 100 times: depth stays log n
  const PointBoxTree dup(same);
  EXPECT_EQ(query(dup, Vec2(3, 3), 0, 0).size(), 100u);
}

// Weighted queries: only the points of weight ≥ wmin, whole light subtrees skipped; the
// weights cluster (light band, heavy outside) as boxWeights do near a boundary layer.
TEST(PointBoxTree, WeightedQueriesReportEveryHeavyEnoughPointInside) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> pts;
  std::vector<double> w;
  for (int i = 0; i < 4000; ++i) {
    const bool band = i % 4 != 0;
    pts.emplace_back(u(rng), band ? 0.5 + 1e-3 * (u(rng) - 0.5) : u(rng));
    w.push_back(band ? 1e-6 * (1 + u(rng)) : 1e-2 * (1 + u(rng)));
  }
  w[17] = w[18];  // a tie: reported, since the bound is ≥
  const PointBoxTree tree(pts, w);
  for (int q = 0; q < 300; ++q) {
    const Vec2 p = pts[std::size_t(q * 13)];
    const double rx = 0.1 * u(rng), ry = q % 2 ? 0.1 * u(rng) : 1e-3 * u(rng);
    const double wmin = q % 3 == 0 ? 0.0 : w[std::size_t(q * 13)];
    std::vector<int> got, want;
    tree.forEachInBoxFrom(p, rx, ry, wmin, [&](int id) { got.push_back(id); });
    std::sort(got.begin(), got.end());
    for (int id : bruteForce(pts, p, rx, ry))
      if (w[std::size_t(id)] >= wmin) want.push_back(id);
    EXPECT_EQ(got, want) << "query " << q;
  }
  std::vector<int> tie;
  tree.forEachInBoxFrom(pts[18], 0, 0, w[18], [&](int id) { tie.push_back(id); });
  EXPECT_NE(std::find(tie.begin(), tie.end(), 18), tie.end());
}
