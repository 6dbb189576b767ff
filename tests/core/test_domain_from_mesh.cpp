// Mirrors core/domain_from_mesh.hpp: the loops of a mesh's boundary, as a Domain.
#include "ablmg/core/domain_from_mesh.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ablmg;

namespace {

/// [0, 3]² (tags 1–4 as Domain::rectangle) minus the hole [1, 2]² (tag 5), as a structured mesh.
Mesh2 squareWithHoleMesh() {
  const BoundaryLoop outer = BoundaryLoop::polygon({{0, 0}, {3, 0}, {3, 3}, {0, 3}}, {1, 2, 3, 4});
  const BoundaryLoop hole = BoundaryLoop::polygon({{1, 1}, {2, 1}, {2, 2}, {1, 2}}, {5, 5, 5, 5});
  return fem::structuredMesh(Domain(std::move(outer), {std::move(hole)}), 6, 6, 0.1, 3);
}

std::string inputErrorOf(const Mesh2& mesh) {
  try {
    domainFromMeshBoundary(mesh, "m.mesh");
  } catch (const InputError& e) { return e.what(); }
  return "";
}

}  // namespace

TEST(DomainFromMesh, OuterLoopAndHoleWithTheirTagsAndArea) {
  const Mesh2 mesh = squareWithHoleMesh();
  ASSERT_TRUE(mesh.validate().ok);
  const Domain d = domainFromMeshBoundary(mesh);
  ASSERT_EQ(d.loops().size(), 2u);
  EXPECT_NEAR(d.area(), mesh.area(), 1e-12);
  EXPECT_NEAR(d.area(), 8.0, 1e-12);
  // Outer: 4 sides of 6 boundary edges (cells 0.5 wide); hole: 4 sides of 2.
  EXPECT_EQ(d.outer().points.size(), 24u);
  EXPECT_EQ(d.loops()[1].points.size(), 8u);
  for (const auto& loop : d.loops()) {
    EXPECT_TRUE(loop.smooth);
    ASSERT_EQ(loop.tags.size(), loop.points.size());
    for (std::size_t k = 0; k < loop.points.size(); ++k) {
      const Vec2 mid = 0.5 * (loop.points[k] + loop.points[(k + 1) % loop.points.size()]);
      const int expected = mid.y() == 0 ? 1 : mid.x() == 3 ? 2 : mid.y() == 3 ? 3 : mid.x() == 0 ? 4 : 5;
      EXPECT_EQ(loop.tags[k], expected) << "segment " << k << " at (" << mid.transpose() << ")";
    }
  }
  // Only the eight square corners are fixed (the other points are on straight sides).
  EXPECT_EQ(d.corners(0).size(), 4u);
  EXPECT_EQ(d.corners(1).size(), 4u);
}

TEST(DomainFromMesh, SegmentsTakeTheRefOfTheirBoundaryEdge) {
  Mesh2 mesh = fem::unitSquareMesh(2);
  for (auto& e : mesh.boundaryEdges) e.ref = 7;
  const Domain d = domainFromMeshBoundary(mesh);
  for (int tag : d.outer().tags) EXPECT_EQ(tag, 7);
}

TEST(DomainFromMesh, LoopsTouchingAtAVertexAreRefused) {
  // Two triangles sharing only vertex 2 (1-based 3 in the message, as in a medit file).
  Mesh2 bowtie;
  bowtie.vertices = {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}};
  bowtie.triangles = {{0, 1, 2}, {2, 3, 4}};
  bowtie.boundaryEdges = {{0, 1, 1}, {1, 2, 1}, {2, 0, 1}, {2, 3, 2}, {3, 4, 2}, {4, 2, 2}};
  EXPECT_EQ(inputErrorOf(bowtie), "m.mesh: boundary vertex 3 starts two boundary edges (non-manifold boundary)");
}

TEST(DomainFromMesh, EmptyMeshIsRefused) { EXPECT_EQ(inputErrorOf(Mesh2{}), "m.mesh: mesh has no boundary edges"); }
