// Mirrors mesher/triangulation.hpp: the scaffold stays a valid triangulation through
// insertion, edge recovery, classification and flips, and insertion gives Delaunay.
#include "ablmg/mesher/triangulation.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// The inside triangles as a Mesh2 with `boundary` as its boundary edges.
Mesh2 insideMesh(const Triangulation& t, std::span<const Vec2> pts, std::span<const std::array<int, 2>> boundary) {
  Mesh2 m;
  m.vertices.assign(pts.begin(), pts.end());
  for (int s = 0; s < t.numTriangleSlots(); ++s)
    if (t.inside(s)) m.triangles.push_back(t.triangle(s));
  for (auto [a, b] : boundary) m.boundaryEdges.push_back({a, b, 1});
  return m;
}

std::vector<std::array<int, 2>> squareBoundary(std::vector<Vec2>& pts, int perSide) {
  std::vector<std::array<int, 2>> b;
  const int first = int(pts.size());
  const Vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k < perSide; ++k)
      pts.push_back(corners[s] + (corners[(s + 1) % 4] - corners[s]) * (double(k) / perSide));
  const int n = int(pts.size()) - first;
  for (int k = 0; k < n; ++k) b.push_back({first + k, first + (k + 1) % n});
  return b;
}

}  // namespace

TEST(Triangulation, RandomPointsGiveADelaunayTriangulation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  std::vector<Vec2> pts;
  auto boundary = squareBoundary(pts, 10);
  for (int i = 0; i < 400; ++i) pts.emplace_back(u(rng), u(rng));
  Triangulation t(pts);
  for (auto [a, b] : boundary) ASSERT_TRUE(t.recoverEdge(a, b));  // already Delaunay edges of a convex hull
  t.classify(boundary);
  const Mesh2 m = insideMesh(t, pts, boundary);
  const auto v = m.validate(1.0);
  ASSERT_TRUE(v.ok) << v.firstProblem;
  EXPECT_EQ(m.numTriangles(), 2 * int(pts.size()) - 40 - 2);  // Euler: 2N − Nb − 2
  // Empty circumcircles (checked against every point, with a small relative margin).
  for (const auto& tr : m.triangles) {
    const Vec2 &a = pts[tr[0]], &b = pts[tr[1]], &c = pts[tr[2]];
    const double d = 2 * cross(b - a, c - a);
    const Vec2 centre = a + Vec2((c - a).y() * (b - a).squaredNorm() - (b - a).y() * (c - a).squaredNorm(),
                                 (b - a).x() * (c - a).squaredNorm() - (c - a).x() * (b - a).squaredNorm()) /
                                d;
    const double r2 = (a - centre).squaredNorm();
    for (const auto& p : pts) EXPECT_GE((p - centre).squaredNorm(), r2 * (1 - 1e-9));
  }
}

TEST(Triangulation, ConstraintsAcrossManyTrianglesAreRecovered) {
  // Points on a fine grid with a few long constraint chords: recovery flips through them.
  std::vector<Vec2> pts;
  auto boundary = squareBoundary(pts, 20);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (int i = 1; i < 20; ++i)
    for (int j = 1; j < 20; ++j) pts.emplace_back(i / 20.0 + jitter(rng), j / 20.0 + jitter(rng));
  const int a = int(pts.size());
  pts.emplace_back(0.1, 0.52);
  pts.emplace_back(0.9, 0.47);
  Triangulation t(pts);
  for (auto [p, q] : boundary) ASSERT_TRUE(t.recoverEdge(p, q));
  EXPECT_TRUE(t.recoverEdge(a, a + 1));
  EXPECT_TRUE(t.hasEdge(a, a + 1));
  EXPECT_TRUE(t.isLocked(a, a + 1));
  t.classify(boundary);
  const auto v = insideMesh(t, pts, boundary).validate(1.0);
  EXPECT_TRUE(v.ok) << v.firstProblem;
}

TEST(Triangulation, ANodeOnTheSegmentRefusesRecovery) {
  std::vector<Vec2> pts{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.25, 0.25}, {0.2, 0.7}};
  Triangulation t(pts);
  EXPECT_FALSE(t.recoverEdge(0, 2));  // (0.5,0.5) and (0.25,0.25) lie on it
  EXPECT_FALSE(t.hasEdge(0, 2));
}

TEST(Triangulation, DuplicatePointsAreAnInputError) {
  std::vector<Vec2> pts{{0, 0}, {1, 0}, {0, 1}, {1, 0}};
  EXPECT_THROW(Triangulation{pts}, InputError);
  std::vector<Vec2> bad{{0, 0}, {1, 0}, {0, NAN}};
  EXPECT_THROW(Triangulation{bad}, InputError);
}

TEST(Triangulation, FlipsKeepTheMeshValidWhateverTheCriterion) {
  std::vector<Vec2> pts;
  auto boundary = squareBoundary(pts, 8);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int i = 0; i < 200; ++i) pts.emplace_back(u(rng), u(rng));
  Triangulation t(pts);
  for (auto [a, b] : boundary) ASSERT_TRUE(t.recoverEdge(a, b));
  t.classify(boundary);
  // An adversarial criterion (flip everything) must stop at the cap and stay valid.
  bool capHit = false;
  const long flips = t.flipWhile([](int, int, int, int) { return true; }, 5000, capHit);
  EXPECT_TRUE(capHit);
  EXPECT_EQ(flips, 5000);
  const auto v = insideMesh(t, pts, boundary).validate(1.0);
  EXPECT_TRUE(v.ok) << v.firstProblem;
}
