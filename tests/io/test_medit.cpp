// Tests of io/medit.hpp: round trips, files in MMG / FreeFem++ / Gmsh style, and bad files
// that must throw InputError naming file:line (never crash).
#include "io/medit.hpp"

#include "core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

using namespace ablmg;
static const std::string kData = ABLMG_TEST_DATA;

static std::string tmpPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("ablmg_io_" + std::to_string(::getpid()) + "_" + name)).string();
}

/// Runs f, expects InputError whose message contains every needle.
template <class F>
static void expectInputError(F f, std::initializer_list<std::string> needles) {
  try {
    f();
    FAIL() << "no exception";
  } catch (const InputError& e) {
    for (const auto& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
  }
}

TEST(Medit, ReadsMmgStyleMeshSkippingUnknownSections) {
  const Mesh2 m = io::readMesh(kData + "/square.mesh");
  EXPECT_EQ(m.numVertices(), 5);
  EXPECT_EQ(m.numTriangles(), 4);
  ASSERT_EQ(m.boundaryEdges.size(), 4u);
  EXPECT_EQ(m.boundaryEdges[1].ref, 2);
  EXPECT_EQ(m.vertexRefs[4], 0);
  EXPECT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
}

TEST(Medit, MeshRoundTripIsExact) {
  Mesh2 m = io::readMesh(kData + "/square.mesh");
  m.vertices[4] = Vec2(0.1 + 1e-13, 1.0 / 3.0);  // needs 17 digits to survive
  m.vertices[0] = Vec2(-2.5e17, 4.9e-324);         // huge and subnormal: shortest forms read back exactly
  m.vertices[1] = Vec2(std::nextafter(1.0, 2.0), -0.0);
  const auto p = tmpPath("rt.mesh");
  io::writeMesh(p, m);
  const Mesh2 r = io::readMesh(p);
  ASSERT_EQ(r.numVertices(), m.numVertices());
  for (int i = 0; i < m.numVertices(); ++i) EXPECT_EQ(r.vertices[i], m.vertices[i]);
  EXPECT_EQ(r.triangles, m.triangles);
  EXPECT_EQ(r.triangleRefs, m.triangleRefs);
  EXPECT_EQ(r.vertexRefs, m.vertexRefs);
  ASSERT_EQ(r.boundaryEdges.size(), m.boundaryEdges.size());
  for (std::size_t e = 0; e < m.boundaryEdges.size(); ++e) {
    EXPECT_EQ(r.boundaryEdges[e].a, m.boundaryEdges[e].a);
    EXPECT_EQ(r.boundaryEdges[e].ref, m.boundaryEdges[e].ref);
  }
  std::filesystem::remove(p);
}

TEST(Medit, TensorSolRoundTripIsExact) {
  std::vector<Metric2> ms = {Metric2::fromSizes(0.1, 0.01, 0.3), Metric2::fromSizes(1, 1, 0), Metric2::fromTensor(3, -1.25, 7)};
  const auto p = tmpPath("rt.sol");
  io::writeSol(p, ms);
  const auto r = io::readSol(p, 3);
  ASSERT_EQ(r.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(r[i].m11(), ms[i].m11());
    EXPECT_EQ(r[i].m12(), ms[i].m12());
    EXPECT_EQ(r[i].m22(), ms[i].m22());
  }
  std::filesystem::remove(p);
}

TEST(Medit, NumbersInEveryStrtodFormReadTheSame) {
  // The fast from_chars path and the strtod fallback must agree: '+' signs, exponents, a
  // leading '.', an underflow to a subnormal, an int written "+3".
  const std::string text = "MeshVersionFormatted 2\nDimension 2\nVertices\n+3\n"
                           "+1.5 .25 +1\n1e-310 -2E+3 0\n0.1 1.0 2\n"
                           "Triangles\n1\n1 2 3 0\nEnd\n";
  const auto p = tmpPath("forms.mesh");
  {
    std::ofstream os(p);
    os << text;
  }
  const Mesh2 m = io::readMesh(p);
  ASSERT_EQ(m.numVertices(), 3);
  EXPECT_EQ(m.vertices[0], Vec2(1.5, 0.25));
  EXPECT_EQ(m.vertices[1], Vec2(std::strtod("1e-310", nullptr), -2000.0));
  EXPECT_EQ(m.vertices[2], Vec2(0.1, 1.0));
  EXPECT_EQ(m.vertexRefs[0], 1);
  std::filesystem::remove(p);
}

TEST(Medit, ScalarSolIsIsotropicSize) {
  const auto r = io::readSol(kData + "/square_scalar.sol", 5);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_NEAR(r[4].eigen().h1, 0.05, 1e-15);
  EXPECT_NEAR(r[4].eigen().h2, 0.05, 1e-15);
  EXPECT_DOUBLE_EQ(r[0].m11(), 100.0);
  const auto p = tmpPath("scalar.sol");
  io::writeScalarSol(p, std::vector<double>{0.5, 0.25, 2});
  const auto back = io::readSol(p);
  EXPECT_DOUBLE_EQ(back[1].m22(), 16.0);
  std::filesystem::remove(p);
}

TEST(Medit, ReadsTensorSolInMmgOrder) {
  const auto r = io::readSol(kData + "/square.sol", 5);
  EXPECT_EQ(r[2].m11(), 400);  // m11 m12 m22
  EXPECT_EQ(r[2].m22(), 25);
  EXPECT_EQ(r[4].m12(), 50);
  EXPECT_NEAR(r[2].eigen().h1, 0.2, 1e-15);
}

TEST(Medit, ReadsFreeFemFilesAndReorientsClockwiseTriangles) {
  const Mesh2 m = io::readMesh(kData + "/freefem.mesh");
  EXPECT_EQ(m.numTriangles(), 2);
  EXPECT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
  const auto s = io::readSol(kData + "/freefem.sol", m.numVertices());
  EXPECT_EQ(s[3].m11(), 9);
  EXPECT_EQ(s[1].m12(), 1);
}

TEST(Medit, ReadsGmshPlanarDimension3) {
  const Mesh2 m = io::readMesh(kData + "/gmsh.mesh");
  EXPECT_EQ(m.numVertices(), 4);
  EXPECT_EQ(m.vertexRefs[2], 3);
  for (int t = 0; t < m.numTriangles(); ++t) EXPECT_GT(m.triangleArea(t), 0);
  EXPECT_EQ(m.boundaryEdges[0].ref, 5);
}

TEST(Medit, KeywordsCaseInsensitiveAndComments) {
  const Mesh2 m = io::parseMesh("meshversionformatted 2 # c\ndimension 2\nVERTICES 3\n0 0 0\n1 0 0\n0 1 0 # v3\ntriangles 1 1 2 3 4\nend\n", "x.mesh");
  EXPECT_EQ(m.numTriangles(), 1);
  EXPECT_EQ(m.triangleRefs[0], 4);
}

TEST(Medit, BadFilesNameFileAndLine) {
  expectInputError([] { io::readMesh(kData + "/truncated.mesh"); }, {"truncated.mesh:7:", "unexpected end of file"});
  expectInputError([] { io::readMesh(kData + "/nan.mesh"); }, {"nan.mesh:7:", "not finite"});
  expectInputError([] { io::readMesh(kData + "/bad_index.mesh"); }, {"bad_index.mesh:10:", "vertex index 7 out of range [1, 3]"});
  expectInputError([] { io::readMesh(kData + "/empty.mesh"); }, {"empty.mesh:1:", "empty file"});
  expectInputError([] { io::readMesh(kData + "/garbage.mesh"); }, {"garbage.mesh:5:"});
  expectInputError([] { io::readMesh(kData + "/does-not-exist.mesh"); }, {"does-not-exist.mesh", "cannot open"});
  expectInputError([] { io::readSol(kData + "/nonspd.sol", 5); },
                   {"nonspd.sol:13: tensor of vertex 5 (1, 2, 1) is not positive definite"});
  expectInputError([] { io::readSol(kData + "/negative-size.sol", 5); }, {"negative-size.sol:8:", "size of vertex 3 is -0.2"});
  expectInputError([] { io::readSol(kData + "/mismatch.sol", 5); }, {"mismatch.sol:4:", "3 solution values but the mesh has 5 vertices"});
  expectInputError([] { io::readSol(kData + "/square.mesh"); }, {"square.mesh", "no SolAtVertices"});
}

TEST(Medit, HugeCountDoesNotAllocate) {
  expectInputError([] { io::parseMesh("MeshVersionFormatted 2\nDimension 2\nVertices\n2000000000\n0 0 0\n", "huge.mesh"); },
                   {"huge.mesh:4:", "more than the file can hold"});
}

// Fuzz-like: every prefix and random byte corruptions of valid files either parse or throw
// InputError (never crash, never another exception type).
TEST(Medit, TruncatedAndGarbledInputsOnlyThrowInputError) {
  const std::string mesh = "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n"
                           "Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\nTriangles\n4\n1 2 5 0\n2 3 5 0\n3 4 5 0\n4 1 5 0\nEnd\n";
  const std::string sol = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 3\n1 0 1\n2 0.5 3\n4 0 4\nEnd\n";
  std::mt19937_64 rng(7);
  long parsed = 0, rejected = 0;
  for (const auto* text : {&mesh, &sol}) {
    const bool isMesh = text == &mesh;
    std::vector<std::string> inputs;
    for (std::size_t n = 0; n < text->size(); ++n) inputs.push_back(text->substr(0, n));
    for (int k = 0; k < 400; ++k) {
      std::string t = *text;
      for (int c = 0; c < 3; ++c) t[rng() % t.size()] = char(rng() % 256);
      inputs.push_back(t);
    }
    for (const auto& in : inputs) {
      try {
        if (isMesh) io::parseMesh(in, "f.mesh"); else io::parseSol(in, "f.sol");
        ++parsed;
      } catch (const InputError& e) {
        ++rejected;
        EXPECT_EQ(std::string(e.what()).rfind("f.", 0), 0u) << e.what();
      }
    }
  }
  EXPECT_GT(rejected, 100);
  EXPECT_GT(parsed, 0);
}

TEST(Medit, SurfaceMeshWritesDimension3) {
  const auto p = tmpPath("surf.mesh");
  io::writeSurfaceMesh(p, {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}}, {{0, 1, 2}});
  EXPECT_THROW(io::readMesh(p), InputError);  // z ≠ 0: not a planar mesh
  std::filesystem::remove(p);
}

// freefem_square.mesh was written by FreeFem++ 4.9: savemesh(square(3, 2, [2*x, y]), ...).
// It carries Identifier/Geometry sections with quoted strings and "Dimension" on its own line.
TEST(Medit, ReadsRealFreeFemOutput) {
  const Mesh2 m = io::readMesh(kData + "/freefem_square.mesh");
  EXPECT_EQ(m.numVertices(), 12);
  EXPECT_EQ(m.numTriangles(), 12);
  ASSERT_EQ(m.boundaryEdges.size(), 10u);
  EXPECT_EQ(m.boundaryEdges[3].ref, 2);
  const auto v = m.validate(2.0);
  EXPECT_TRUE(v.ok) << v.firstProblem;
  EXPECT_THROW(io::parseMesh("MeshVersionFormatted 1\nDimension 2\nIdentifier\n\"never closed\n", "q.mesh"), InputError);
}

TEST(Medit, Dimension3PlanarTensorSol) {
  const auto r = io::parseSol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 3\n4 1 0 9 0 1\nEnd\n", "d3.sol");
  EXPECT_EQ(r[0].m11(), 4);
  EXPECT_EQ(r[0].m12(), 1);
  EXPECT_EQ(r[0].m22(), 9);
  EXPECT_THROW(io::parseSol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 3\n4 1 0.5 9 0 1\nEnd\n", "d3.sol"), InputError);
}
