// io/medit.hpp readSurfaceMesh: a surface written by writeSurfaceMesh reads back exactly; a
// planar file reads with z = 0; errors are the same file:line InputErrors as readMesh's.
#include "ablmg/io/medit.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace ablmg;

TEST(MeditSurface, RoundTripOfWriteSurfaceMesh) {
  const auto p =
      (std::filesystem::temp_directory_path() / ("ablmg_surf_" + std::to_string(::getpid()) + ".mesh")).string();
  const std::vector<Eigen::Vector3d> v{{0, 0, 0}, {1, 0, 0.1}, {0, 1, 1.0 / 3}};
  io::writeSurfaceMesh(p, v, {{0, 2, 1}}, {7});
  const io::SurfaceMeshFile f = io::readSurfaceMesh(p);
  std::filesystem::remove(p);
  EXPECT_EQ(f.dimension, 3);
  EXPECT_EQ(f.vertices, v);  // shortest round-trip form: exact
  ASSERT_EQ(f.triangles.size(), 1u);
  EXPECT_EQ(f.triangles[0], (std::array<int, 3>{0, 2, 1}));  // file orientation kept
  EXPECT_EQ(f.triangleRefs, std::vector<int>{7});
}

TEST(MeditSurface, PlanarFileHasZeroZAndErrorsNameTheLine) {
  const io::SurfaceMeshFile f = io::readSurfaceMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh");
  EXPECT_EQ(f.dimension, 2);
  ASSERT_EQ(f.vertices.size(), 5u);
  EXPECT_EQ(f.vertices[4], Eigen::Vector3d(0.5, 0.5, 0));
  EXPECT_EQ(f.triangles.size(), 4u);
  try {
    io::parseSurfaceMesh("MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 nan 1\nEnd\n", "bad.mesh");
    FAIL() << "no exception";
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("bad.mesh:5:"), std::string::npos) << e.what(); }
}
