#include "ablmg/core/bucket_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace ablmg;

TEST(BucketGrid, StaticQueryFindsEveryPointInTheBox) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 5);
  std::vector<Vec2> pts(2000);
  for (auto& p : pts) p = Vec2(u(rng), 0.5 * u(rng));
  BucketGrid g(Vec2(-2, -1), Vec2(5, 2.5), 0.3);
  g.build(pts);
  for (int q = 0; q < 50; ++q) {
    const Vec2 c(u(rng), 0.5 * u(rng));
    const double r = 0.05 + 0.1 * (q % 7);
    std::vector<int> got, want;
    g.forEach(c, r, [&](int id) {
      if ((pts[id] - c).cwiseAbs().maxCoeff() <= r) got.push_back(id);
    });
    for (int i = 0; i < int(pts.size()); ++i)
      if ((pts[i] - c).cwiseAbs().maxCoeff() <= r) want.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want);
  }
}

TEST(BucketGrid, IncrementalMatchesStaticAndClampsOutsidePoints) {
  std::vector<Vec2> pts = {{0, 0}, {1, 1}, {10, 10}, {-5, 0.5}, {0.5, 0.5}};
  BucketGrid g(Vec2(0, 0), Vec2(1, 1), 0.25);
  g.clearIncremental();
  for (int i = 0; i < int(pts.size()); ++i) g.insert(i, pts[i]);
  std::vector<int> got;
  g.forEachIncremental(Vec2(1, 1), 0.1, [&](int id) { got.push_back(id); });
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<int>{1, 2}));  // (10,10) is clamped into the corner cell
  g.build(pts);
  int total = 0;
  for (int c = 0; c < g.numCells(); ++c) total += int(g.cell(c).size());
  EXPECT_EQ(total, 5);
}

TEST(BucketGrid, IncrementalBoxQueryFindsEveryPointInAThinBox) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> pts(3000);
  for (auto& p : pts) p = Vec2(u(rng), u(rng));
  BucketGrid g(Vec2(0, 0), Vec2(1, 1), 0.02);
  g.clearIncremental();
  for (int i = 0; i < int(pts.size()); ++i) g.insert(i, pts[i]);
  for (int q = 0; q < 200; ++q) {
    const Vec2 c(u(rng), u(rng));
    const double rx = q % 2 ? 0.3 : 1e-4, ry = q % 2 ? 1e-4 : 0.3;  // anisotropy 3·10³ either way
    const auto inBox = [&](int id) {
      return std::abs(pts[id].x() - c.x()) <= rx && std::abs(pts[id].y() - c.y()) <= ry;
    };
    bool want = false;
    for (int i = 0; i < int(pts.size()); ++i) want = want || inBox(i);
    EXPECT_EQ(g.anyIncremental(c, rx, ry, inBox), want) << "query " << q;
  }
}

TEST(BucketGrid, CellCountIsCapped) {
  BucketGrid g(Vec2(0, 0), Vec2(1000, 1000), 1e-3, 10000);
  EXPECT_LE(long(g.nx()) * g.ny(), 10000);
}
