#include "ablmg/core/mesh2.hpp"

#include <gtest/gtest.h>

using namespace ablmg;

namespace {
/// Unit square split into two triangles, boundary CCW.
Mesh2 twoTriangles() {
  Mesh2 m;
  m.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.boundaryEdges = {{0, 1, 1}, {1, 2, 2}, {2, 3, 3}, {3, 0, 4}};
  return m;
}
}  // namespace

TEST(Mesh2, ValidMeshPasses) {
  const Mesh2 m = twoTriangles();
  const auto r = m.validate(1.0);
  EXPECT_TRUE(r.ok) << r.firstProblem;
  EXPECT_DOUBLE_EQ(r.area, 1.0);
  EXPECT_EQ(m.edges().size(), 5u);
  const auto nb = m.triangleNeighbours();
  EXPECT_EQ(nb[0][1], 1);  // edge opposite vertex 1 of triangle 0 is (2,0)
}

TEST(Mesh2, CatchesInvertedTriangle) {
  Mesh2 m = twoTriangles();
  m.triangles[1] = {0, 3, 2};
  const auto r = m.validate();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.invertedTriangles, 1);
  EXPECT_NE(r.firstProblem.find("inverted"), std::string::npos);
}

TEST(Mesh2, CatchesMissingTriangle) {
  Mesh2 m = twoTriangles();
  m.triangles.pop_back();
  m.vertices.pop_back();
  m.boundaryEdges = {{0, 1, 1}, {1, 2, 2}, {2, 3, 3}, {3, 0, 4}};
  m.vertices.push_back({0, 1});
  const auto r = m.validate();
  EXPECT_FALSE(r.ok);  // vertex 3 unused, edge (0,2) open, boundary edges (2,3),(3,0) without triangle
  EXPECT_GT(r.openEdges, 0);
}

TEST(Mesh2, CatchesOverlapAndWrongArea) {
  Mesh2 m = twoTriangles();
  m.triangles.push_back({0, 1, 2});  // duplicate: edge (0,1) in two triangles, same orientation
  EXPECT_FALSE(m.validate().ok);
  const Mesh2 ok = twoTriangles();
  EXPECT_FALSE(ok.validate(1.5).ok);
  EXPECT_TRUE(ok.validate(1.0 + 1e-12).ok);
}

TEST(Mesh2, CatchesNonFiniteAndOutOfRange) {
  Mesh2 m = twoTriangles();
  m.vertices[2].x() = NAN;
  EXPECT_FALSE(m.validate().ok);
  Mesh2 n = twoTriangles();
  n.triangles[0][2] = 9;
  EXPECT_FALSE(n.validate().ok);
}

namespace {
/// The unit square as an n × n grid of squares, each cut into two triangles, boundary CCW.
Mesh2 gridSquare(int n) {
  Mesh2 m;
  const auto v = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back({double(i) / n, double(j) / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  for (int i = 0; i < n; ++i) {
    m.boundaryEdges.push_back({v(i, 0), v(i + 1, 0), 1});
    m.boundaryEdges.push_back({v(n, i), v(n, i + 1), 2});
    m.boundaryEdges.push_back({v(n - i, n), v(n - i - 1, n), 3});
    m.boundaryEdges.push_back({v(0, n - i), v(0, n - i - 1), 4});
  }
  return m;
}
}  // namespace

// 80 000 triangles: the parallel passes of validate() and triangleNeighbours(); the same
// verdicts and neighbours as the serial definitions.
TEST(Mesh2, LargeMeshParallelChecks) {
  const int n = 200;
  Mesh2 m = gridSquare(n);
  const auto r = m.validate(1.0);
  EXPECT_TRUE(r.ok) << r.firstProblem;
  EXPECT_NEAR(r.area, 1.0, 1e-12);
  const auto nb = m.triangleNeighbours();
  long interior = 0;
  for (int t = 0; t < m.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = nb[std::size_t(t)][std::size_t(k)];
      if (u < 0) continue;
      ++interior;
      const auto& back = nb[std::size_t(u)];
      EXPECT_TRUE(back[0] == t || back[1] == t || back[2] == t) << t << " " << u;
    }
  EXPECT_EQ(interior, 2L * (3L * n * n - 2L * n));  // interior edges, each seen from both sides
  EXPECT_EQ(m.edges().size(), std::size_t(3 * n * n + 2 * n));

  Mesh2 flipped = m;  // one inverted triangle, named
  std::swap(flipped.triangles[40001][1], flipped.triangles[40001][2]);
  const auto f = flipped.validate(1.0);
  EXPECT_FALSE(f.ok);
  EXPECT_EQ(f.invertedTriangles, 1);
  EXPECT_NE(f.firstProblem.find("triangle 40001 "), std::string::npos) << f.firstProblem;

  Mesh2 holed = m;  // one triangle missing: its three edges are open
  holed.triangles.erase(holed.triangles.begin() + 30000);
  const auto h = holed.validate();
  EXPECT_FALSE(h.ok);
  EXPECT_EQ(h.openEdges, 3);

  Mesh2 split = m;  // an interior edge between two subdomains, not an interface edge
  split.triangleRefs.assign(m.triangles.size(), 1);
  split.triangleRefs[20000] = 2;
  const auto s = split.validate();
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.firstProblem.find("separates subdomains"), std::string::npos) << s.firstProblem;
}
