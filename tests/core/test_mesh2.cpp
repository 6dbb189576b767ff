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
