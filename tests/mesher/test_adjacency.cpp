#include "ablmg/mesher/adjacency.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

struct Cloud {
  std::vector<Vec2> x;
  std::vector<Metric2> m;
};

Cloud randomCloud(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const Vec2 p(4 * u(rng), 2 * u(rng));
    const double h = 0.03 + 0.1 * p.x() / 4;  // graded and anisotropic
    c.x.push_back(p);
    c.m.push_back(Metric2::fromSizes(h, 0.4 * h, p.y()));
  }
  return c;
}

/// A boundary layer: sizes 10⁻³ × 1 across y = 0.5 (anisotropy 10³) growing to isotropic
/// 0.05 away from it, nodes at the density the metric asks for in the band, sparse outside;
/// the sizes change fast across the band, so a pair's two boxes differ by orders of magnitude.
Cloud layerCloud(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const bool band = i % 5 != 0;
    const Vec2 p(u(rng), band ? 0.5 + 0.004 * (u(rng) - 0.5) : u(rng));
    const double d = std::min(1.0, std::abs(p.y() - 0.5) / 0.01);
    c.x.push_back(p);
    c.m.push_back(Metric2::fromSizes(0.02 + 0.03 * d, 1e-3 + 0.049 * d, 0.0));
  }
  return c;
}

/// A hexagonal packing of na × nb bubbles at spacing 0.05, each jittered by up to ±0.005 (draws
/// from `jitter`, uniform in [−1, 1]), sizes graded along the rows, h = 0.05 (1 + amp sin(freq a)),
/// with aspect `ratio` at angle `theta`.
Cloud jitteredPacking(int na, int nb, double amp, double freq, double ratio, double theta, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> jitter(-1, 1);
  Cloud c;
  for (int a = 0; a < na; ++a)
    for (int b = 0; b < nb; ++b) {
      const double h = 0.05 * (1 + amp * std::sin(freq * a));
      c.x.push_back(Vec2(0.05 * (a + 0.5 * b) + 0.005 * jitter(rng), 0.05 * 0.866 * b + 0.005 * jitter(rng)));
      c.m.push_back(Metric2::fromSizes(h, ratio * h, theta));
    }
  return c;
}

/// A population edit: c without its nodes i with i % k == r, then `extra` appended; map old →
/// new id (−1 = deleted), new nodes from firstNew.
struct EditedCloud {
  Cloud cloud;
  std::vector<int> map;
  int firstNew = 0;
};
EditedCloud dropAndAppend(const Cloud& c, int k, int r, const Cloud& extra) {
  EditedCloud e;
  e.map.assign(c.x.size(), -1);
  for (int i = 0; i < int(c.x.size()); ++i)
    if (i % k != r) {
      e.map[std::size_t(i)] = int(e.cloud.x.size());
      e.cloud.x.push_back(c.x[std::size_t(i)]);
      e.cloud.m.push_back(c.m[std::size_t(i)]);
    }
  e.firstNew = int(e.cloud.x.size());
  e.cloud.x.insert(e.cloud.x.end(), extra.x.begin(), extra.x.end());
  e.cloud.m.insert(e.cloud.m.end(), extra.m.begin(), extra.m.end());
  return e;
}

/// The lists of `old` patched for the edit equal the lists rebuilt from scratch.
void expectPatchEqualsRebuild(const AdjacencyLists& old, const EditedCloud& e) {
  const Cloud& d = e.cloud;
  const AdjacencyLists p = patchAdjacency(old, e.map, e.firstNew, d.x, d.m, 1.7);
  const AdjacencyLists b = buildAdjacency(d.x, d.m, 1.7);
  EXPECT_TRUE(p.isSymmetric());
  EXPECT_EQ(p.offsets, b.offsets);
  EXPECT_EQ(p.ids, b.ids);
}

std::vector<std::vector<int>> brute(const Cloud& c, double r) {
  std::vector<std::vector<int>> rows(c.x.size());
  for (int i = 0; i < int(c.x.size()); ++i)
    for (int j = 0; j < int(c.x.size()); ++j)
      if (i != j && withinMetricRadius(c.x[j] - c.x[i], c.m[i], c.m[j], r)) rows[i].push_back(j);
  return rows;
}

}  // namespace

TEST(Adjacency, BuildEqualsBruteForceAndIsSymmetric) {
  const Cloud c = randomCloud(3000, 7);
  const AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  ASSERT_EQ(a.size(), 3000);
  EXPECT_TRUE(a.isSymmetric());
  const auto want = brute(c, 1.7);
  long total = 0;
  for (int i = 0; i < a.size(); ++i) {
    const auto row = a.neighbours(i);
    EXPECT_EQ(std::vector<int>(row.begin(), row.end()), want[i]) << i;
    total += long(row.size());
  }
  EXPECT_GT(total, 3000);  // the test is not vacuous
}

TEST(Adjacency, RefreshAfterSmallMovesEqualsRebuild) {
  // a jittered packing (the refresh relies on every new neighbour being within two hops)
  std::mt19937_64 jr(4);
  Cloud c = jitteredPacking(50, 40, 0.1, 0.1, 0.9, 0.3, jr);
  const AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0, 0.02);
  for (int i = 0; i < int(c.x.size()); ++i) c.x[i] += 0.1 * Vec2(g(rng), g(rng));  // ≈ 0.002 ≪ h
  const AdjacencyLists r = refreshAdjacency(a, c.x, c.m, 1.7);
  const AdjacencyLists b = buildAdjacency(c.x, c.m, 1.7);
  EXPECT_TRUE(r.isSymmetric());
  EXPECT_EQ(r.offsets, b.offsets);
  EXPECT_EQ(r.ids, b.ids);
}

TEST(Adjacency, LocalRefreshAroundMovedBubblesEqualsRebuild) {
  // A jittered packing; 40 bubbles (and only they) move by up to 0.1 of their size: the rows
  // around them are recomputed and the rest patched symmetrically, which must give exactly
  // the lists of a rebuild (rows far from every mover cannot have changed).
  std::mt19937_64 jr(5);
  Cloud c = jitteredPacking(50, 40, 0.1, 0.1, 0.9, 0.3, jr);
  std::uniform_real_distribution<double> ju(-1, 1);
  AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  const AdjacencyLists before = a;
  std::vector<int> movers;
  for (int i = 7; i < int(c.x.size()); i += 50) {
    movers.push_back(i);
    c.x[i] += 0.005 * Vec2(ju(jr), ju(jr));
  }
  refreshAdjacencyAround(a, c.x, c.m, 1.7, movers);
  const AdjacencyLists b = buildAdjacency(c.x, c.m, 1.7);
  EXPECT_TRUE(a.isSymmetric());
  a.compact();
  EXPECT_EQ(a.offsets, b.offsets);
  EXPECT_EQ(a.ids, b.ids);
  EXPECT_NE(before.ids, b.ids);  // not vacuous: the moves changed some rows
}

TEST(Adjacency, RepeatedLocalRefreshesWithRowSlackEqualRebuild) {
  // Ten rounds of small moves of a few bubbles each, refreshed in place: the first round lays
  // the rows out with slack, later ones rewrite rows inside their capacity. After every round
  // the rows read through neighbours() and the compacted lists equal a rebuild.
  std::mt19937_64 jr(8);
  Cloud c = jitteredPacking(40, 30, 0.2, 0.15, 0.8, 0.2, jr);
  std::uniform_real_distribution<double> ju(-1, 1);
  AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  bool sawSlack = false;
  for (int round = 0; round < 10; ++round) {
    std::vector<int> movers;
    for (int i = 3 + round; i < int(c.x.size()); i += 37) {
      movers.push_back(i);
      c.x[i] += 0.006 * Vec2(ju(jr), ju(jr));
    }
    refreshAdjacencyAround(a, c.x, c.m, 1.7, movers);
    sawSlack = sawSlack || !a.ends.empty();
    const AdjacencyLists b = buildAdjacency(c.x, c.m, 1.7);
    ASSERT_TRUE(a.isSymmetric());
    for (int i = 0; i < b.size(); ++i) {
      const auto x = a.neighbours(i), y = b.neighbours(i);
      ASSERT_TRUE(std::equal(x.begin(), x.end(), y.begin(), y.end())) << "round " << round << ", row " << i;
    }
    AdjacencyLists compacted = a;
    compacted.compact();
    EXPECT_TRUE(compacted.ends.empty());
    EXPECT_EQ(compacted.offsets, b.offsets);
    EXPECT_EQ(compacted.ids, b.ids);
  }
  EXPECT_TRUE(sawSlack);  // not vacuous: the slack layout was exercised
}

TEST(Adjacency, IsSymmetricDetectsBrokenLists) {
  AdjacencyLists a;
  a.offsets = {0, 1, 1};
  a.ids = {1};
  EXPECT_FALSE(a.isSymmetric());
  a.offsets = {0, 1, 2};
  a.ids = {1, 0};
  EXPECT_TRUE(a.isSymmetric());
}

TEST(Adjacency, PatchAfterDeletionsAndInsertionsEqualsRebuild) {
  Cloud c = randomCloud(1500, 11);
  const AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  expectPatchEqualsRebuild(a, dropAndAppend(c, 7, 3, randomCloud(40, 12)));  // every 7th node out, 40 in
}

// The 2-d tree's case: in the band a bucket grid of the mean spacing held hundreds of nodes
// per cell. Build and patch still give exactly the pairs within the radius, both ways (a pair
// is in one of its two nodes' boxes only, when their sizes differ 50×).
TEST(Adjacency, BuildAndPatchEqualBruteForceInAStretchedLayer) {
  const Cloud c = layerCloud(2500, 5);
  const AdjacencyLists a = buildAdjacency(c.x, c.m, 1.7);
  EXPECT_TRUE(a.isSymmetric());
  const auto want = brute(c, 1.7);
  long total = 0;
  for (int i = 0; i < a.size(); ++i) {
    const auto row = a.neighbours(i);
    EXPECT_EQ(std::vector<int>(row.begin(), row.end()), want[i]) << i;
    total += long(row.size());
  }
  EXPECT_GT(total, 5 * 2500);
  expectPatchEqualsRebuild(a, dropAndAppend(c, 9, 4, layerCloud(300, 6)));  // every 9th node out, 300 in
}
