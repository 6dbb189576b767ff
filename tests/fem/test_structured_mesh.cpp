// Tests of fem/structured_mesh.hpp: valid meshes, tags, perturbation keeps validity.
#include "ablmg/fem/structured_mesh.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace ablmg;
using namespace ablmg::fem;

TEST(StructuredMesh, UnitSquareCountsAndTags) {
  const Mesh2 m = unitSquareMesh(4);
  EXPECT_EQ(m.numVertices(), 25);
  EXPECT_EQ(m.numTriangles(), 32);
  EXPECT_EQ(m.boundaryEdges.size(), 16u);
  for (const auto& e : m.boundaryEdges) {
    const Vec2 mid = 0.5 * (m.vertices[e.a] + m.vertices[e.b]);
    const int expected = mid.y() == 0 ? 1 : mid.x() == 1 ? 2 : mid.y() == 1 ? 3 : 4;
    EXPECT_EQ(e.ref, expected) << "edge at " << mid.transpose();
  }
  EXPECT_TRUE(m.validate(1.0).ok);
}

TEST(StructuredMesh, LShapeIsValidWithSixTags) {
  const TestProblem p = makeProblem("lshape");
  const Mesh2 m = structuredMesh(p.domain, 8, 8);
  EXPECT_TRUE(m.validate(3.0).ok) << m.validate(3.0).firstProblem;
  EXPECT_EQ(m.numTriangles(), 2 * 48);
  std::set<int> tags;
  for (const auto& e : m.boundaryEdges) tags.insert(e.ref);
  EXPECT_EQ(tags, (std::set<int>{1, 2, 3, 4, 5, 6}));
}

TEST(StructuredMesh, PerturbedMeshesAreValidAndSeeded) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Mesh2 m = unitSquareMesh(7, 0.2, seed);
    EXPECT_TRUE(m.validate(1.0).ok);
  }
  const Mesh2 a = unitSquareMesh(6, 0.2, 5), b = unitSquareMesh(6, 0.2, 5), c = unitSquareMesh(6, 0.2, 6);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_NE(a.vertices, c.vertices);
}

TEST(StructuredMesh, RejectsBadInput) {
  EXPECT_THROW(unitSquareMesh(0), InputError);
  EXPECT_THROW(unitSquareMesh(4, 0.3), InputError);
  EXPECT_THROW(structuredMesh(makeProblem("lshape").domain, 3, 3), InputError);  // corner off-grid
  EXPECT_THROW(structuredMesh(Domain::disk(Vec2(0, 0), 1, 64), 4, 4), InputError);
}
