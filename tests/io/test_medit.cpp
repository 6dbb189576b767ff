// Tests of io/medit.hpp: round trips, files in MMG / FreeFem++ / Gmsh style, and bad files
// that must throw InputError naming file:line (never crash).
#include "ablmg/io/medit.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

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
    for (const auto& n : needles)
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
  }
}

/// Bit equality (tells -0.0 from 0.0, unlike ==).
static bool sameBits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

static std::string fileText(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
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
  m.vertices[4] = Vec2(0.1 + 1e-13, 1.0 / 3.0);  // 17 and 16 significant digits to survive
  m.vertices[0] = Vec2(-2.5e17, 4.9e-324);       // huge and subnormal: shortest forms read back exactly
  m.vertices[1] = Vec2(std::nextafter(1.0, 2.0), -0.0);
  m.vertexRefs[3] = -2147483647 - 1;
  const auto p = tmpPath("rt.mesh");
  io::writeMesh(p, m);
  const Mesh2 r = io::readMesh(p);
  ASSERT_EQ(r.numVertices(), m.numVertices());
  for (int i = 0; i < m.numVertices(); ++i)
    EXPECT_TRUE(sameBits(r.vertices[i].x(), m.vertices[i].x()) && sameBits(r.vertices[i].y(), m.vertices[i].y()))
        << "vertex " << i << ": " << r.vertices[i].transpose() << " vs " << m.vertices[i].transpose();
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
  std::vector<Metric2> ms = {Metric2::fromSizes(0.1, 0.01, 0.3), Metric2::fromSizes(1, 1, 0),
                             Metric2::fromTensor(3, -1.25, 7), Metric2::fromTensor(2.5e7, -0.0, 1.0 / 3.0),
                             Metric2::fromTensor(0.1, 1e-300, 0.2)};
  const auto p = tmpPath("rt.sol");
  io::writeSol(p, ms);
  const auto r = io::readSol(p, int(ms.size()));
  ASSERT_EQ(r.size(), ms.size());
  for (std::size_t i = 0; i < ms.size(); ++i) {
    EXPECT_TRUE(sameBits(r[i].m11(), ms[i].m11())) << i;
    EXPECT_TRUE(sameBits(r[i].m12(), ms[i].m12())) << i;
    EXPECT_TRUE(sameBits(r[i].m22(), ms[i].m22())) << i;
  }
  std::filesystem::remove(p);
}

TEST(Medit, RandomDoublesRoundTripBitForBit) {
  // Awkward values, then random bit patterns (every exponent, subnormals included): the
  // shortest form written by to_chars reads back to the same bits.
  const double awkward[] = {0.1,
                            1e-300,
                            -2.5e17,
                            1.0 / 3.0,
                            -0.0,
                            4.9e-324,
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::min(),
                            123456789012345680.0,
                            5e-324,
                            0.30000000000000004};
  std::mt19937_64 rng(11);
  Mesh2 m = io::readMesh(kData + "/square.mesh");
  m.triangles.clear();  // vertices only: random coordinates would make the reader reorient triangles
  m.triangleRefs.clear();
  m.boundaryEdges.clear();
  for (int round = 0; round < 200; ++round) {
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      double xy[2];
      for (int k = 0; k < 2; ++k) {
        const std::size_t slot = 2 * (std::size_t(round) * m.vertices.size() + i) + std::size_t(k);
        if (slot < std::size(awkward))
          xy[k] = awkward[slot];
        else
          do xy[k] = std::bit_cast<double>(rng());
          while (!std::isfinite(xy[k]));
      }
      m.vertices[i] = Vec2(xy[0], xy[1]);
    }
    const Mesh2 r = io::parseMesh(
        [&] {
          const auto p = tmpPath("random.mesh");
          io::writeMesh(p, m);
          const std::string text = fileText(p);
          std::filesystem::remove(p);
          return text;
        }(),
        "random.mesh");
    for (int i = 0; i < m.numVertices(); ++i)
      ASSERT_TRUE(sameBits(r.vertices[i].x(), m.vertices[i].x()) && sameBits(r.vertices[i].y(), m.vertices[i].y()))
          << std::hexfloat << m.vertices[i].x() << " " << m.vertices[i].y();
  }
}

TEST(Medit, WritesTheMeditLayout) {
  // The layout MMG and FreeFem++ read: keywords on their own lines, blank lines between
  // sections, 1-based indices, shortest doubles.
  Mesh2 m;
  m.vertices = {Vec2(0, 0), Vec2(0.1, -2.5e-7), Vec2(1.0 / 3.0, 1e22)};
  m.vertexRefs = {1, 0, 7};
  m.triangles = {{0, 1, 2}};
  m.triangleRefs = {3};
  m.boundaryEdges = {{0, 1, 5}};
  const auto p = tmpPath("layout.mesh");
  io::writeMesh(p, m);
  EXPECT_EQ(fileText(p),
            "MeshVersionFormatted 2\n\nDimension 2\n\nVertices\n3\n0 0 1\n0.1 -2.5e-07 0\n0.3333333333333333 1e+22 7\n"
            "\nEdges\n1\n1 2 5\n\nTriangles\n1\n1 2 3 3\n\nEnd\n");
  std::filesystem::remove(p);
  io::writeSol(p, std::vector<Metric2>{Metric2::fromTensor(4, 0.5, 1.5e-3 + 0.1)});
  EXPECT_EQ(fileText(p), "MeshVersionFormatted 2\n\nDimension 2\n\nSolAtVertices\n1\n1 3\n\n4 0.5 0.1015\n\nEnd\n");
  io::writeScalarSol(p, std::vector<double>{0.25, 1e-5});
  EXPECT_EQ(fileText(p), "MeshVersionFormatted 2\n\nDimension 2\n\nSolAtVertices\n2\n1 1\n\n0.25\n1e-05\n\nEnd\n");
  std::filesystem::remove(p);
}

TEST(Medit, WriteMeshAndSolWritesWhatTheSingleWritersWrite) {
  const Mesh2 m = io::readMesh(kData + "/square.mesh");
  const auto metrics = io::readSol(kData + "/square.sol", m.numVertices());
  const auto pm = tmpPath("pair.mesh"), ps = tmpPath("pair.sol"), qm = tmpPath("single.mesh"),
             qs = tmpPath("single.sol");
  io::writeMeshAndSol(pm, m, ps, metrics);
  io::writeMesh(qm, m);
  io::writeSol(qs, metrics);
  EXPECT_EQ(fileText(pm), fileText(qm));
  EXPECT_EQ(fileText(ps), fileText(qs));
  for (const auto& p : {pm, ps, qm, qs}) std::filesystem::remove(p);
}

TEST(Medit, WriteMeshAndSolLeavesNoMeshWhenTheSolFails) {
  const Mesh2 m = io::readMesh(kData + "/square.mesh");
  const auto metrics = io::readSol(kData + "/square.sol", m.numVertices());
  const auto pm = tmpPath("blocked.mesh"), ps = tmpPath("blocked.sol");
  std::filesystem::create_directories(ps);  // a directory where the .sol should go: rename fails
  EXPECT_THROW(io::writeMeshAndSol(pm, m, ps, metrics), Error);
  EXPECT_FALSE(std::filesystem::exists(pm));
  std::filesystem::remove(ps);
}

TEST(Medit, WriteMeshAndSolLeavesTheOldSolWhenTheMeshFails) {
  const Mesh2 m = io::readMesh(kData + "/square.mesh");
  const auto metrics = io::readSol(kData + "/square.sol", m.numVertices());
  const auto pm = tmpPath("blocked2.mesh"), ps = tmpPath("kept.sol");
  io::writeSol(ps, std::vector<Metric2>{Metric2::fromTensor(4, 0.5, 0.1)});
  const std::string before = fileText(ps);
  std::filesystem::create_directories(pm);  // a directory where the .mesh should go: rename fails
  EXPECT_THROW(io::writeMeshAndSol(pm, m, ps, metrics), Error);
  EXPECT_EQ(fileText(ps), before);
  std::filesystem::remove(pm);
  std::filesystem::remove(ps);
}

TEST(Medit, StreamedTextOfManyBlocksReadsBackBitwise) {
  // ≈ 5 MB of .mesh text: the writer hands it over in 1 MB blocks.
  Mesh2 m;
  const int n = 250;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(std::sqrt(2.0) * i / n, double(j) / (3 * n));
  const auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int i = 0; i < n; ++i) {
    m.boundaryEdges.push_back({id(i, 0), id(i + 1, 0), 1});
    m.boundaryEdges.push_back({id(n, i), id(n, i + 1), 2});
    m.boundaryEdges.push_back({id(i + 1, n), id(i, n), 3});
    m.boundaryEdges.push_back({id(0, i + 1), id(0, i), 4});
  }
  std::vector<Metric2> metrics;
  for (const Vec2& p : m.vertices) metrics.push_back(Metric2::fromTensor(1 + p.x(), 0.1 * p.y(), 2 + p.y()));
  const auto pm = tmpPath("big.mesh"), ps = tmpPath("big.sol");
  io::writeMeshAndSol(pm, m, ps, metrics);
  EXPECT_GT(std::filesystem::file_size(pm), std::uintmax_t(3) << 20);
  const Mesh2 r = io::readMesh(pm);
  ASSERT_EQ(r.vertices.size(), m.vertices.size());
  EXPECT_TRUE(r.vertices == m.vertices);
  EXPECT_TRUE(r.triangles == m.triangles);
  const auto rm = io::readSol(ps, r.numVertices());
  ASSERT_EQ(rm.size(), metrics.size());
  for (std::size_t k = 0; k < rm.size(); ++k)
    EXPECT_TRUE(rm[k].m11() == metrics[k].m11() && rm[k].m12() == metrics[k].m12() && rm[k].m22() == metrics[k].m22());
  std::filesystem::remove(pm);
  std::filesystem::remove(ps);
}

TEST(Medit, NumbersInEveryStrtodFormReadTheSame) {
  // The fast from_chars path and the strtod fallback must agree: '+' signs, exponents, a
  // leading '.', an underflow to a subnormal, an int written "+3".
  const std::string text =
      "MeshVersionFormatted 2\nDimension 2\nVertices\n+3\n"
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

TEST(Medit, FastNumberPathKeepsTheMessages) {
  const std::string head = "MeshVersionFormatted 2\nDimension 2\nVertices\n1\n";
  // A number of more than 400 characters is refused, however valid.
  expectInputError([&] { io::parseMesh(head + "0." + std::string(400, '0') + "1 0 0\nEnd\n", "long.mesh"); },
                   {"long.mesh:5:", "expected vertex x coordinate (a number)"});
  expectInputError([&] { io::parseMesh(head + "1e400 0 0\nEnd\n", "big.mesh"); },
                   {"big.mesh:5:", "vertex x coordinate is not finite: '1e400'"});
  expectInputError([&] { io::parseMesh(head + "inf 0 0\nEnd\n", "inf.mesh"); },
                   {"inf.mesh:5:", "is not finite: 'inf'"});
  expectInputError([&] { io::parseMesh(head + "1.5x 0 0\nEnd\n", "x.mesh"); }, {"x.mesh:5:", "got '1.5x'"});
  expectInputError([&] { io::parseMesh(head + "0 0 0x10\nEnd\n", "hex.mesh"); },
                   {"hex.mesh:5:", "(an integer), got '0x10'"});
  expectInputError([&] { io::parseMesh(head + "0 0 99999999999\nEnd\n", "ref.mesh"); },
                   {"ref.mesh:5:", "vertex reference 99999999999 is out of range"});
  expectInputError([&] { io::parseMesh(head + "0 0\n\n", "eof.mesh"); }, {"eof.mesh:5:", "unexpected end of file"});
  // A comment right after a number ends it; the last number may end the file (a .sol: a
  // .mesh needs its End keyword, MeshFile.FileCutBetweenSectionsIsTruncated).
  const Mesh2 m = io::parseMesh(head + "0.5#c\n-0.25 3\nEnd", "ok.mesh");
  EXPECT_EQ(m.vertices[0], Vec2(0.5, -0.25));
  EXPECT_EQ(m.vertexRefs[0], 3);
  const auto sol = io::parseSol("MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n1\n1 1\n0.25", "ok.sol");
  ASSERT_EQ(sol.size(), 1u);
  EXPECT_DOUBLE_EQ(sol[0].m11(), 16.0);
}

TEST(MeshFile, FileCutBetweenSectionsIsTruncated) {
  // Cut after Edges: without the End check it read as a boundary-only file and was meshed.
  const std::string whole =
      "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 1\n1 0 1\n0 1 1\n"
      "Edges\n3\n1 2 1\n2 3 1\n3 1 1\nTriangles\n1\n1 2 3 1\nEnd\n";
  EXPECT_EQ(io::parseMesh(whole, "whole.mesh").numTriangles(), 1);
  expectInputError([&] { io::parseMesh(whole.substr(0, whole.find("Triangles")), "cut.mesh"); },
                   {"cut.mesh:", "no End keyword (truncated file?)"});
}

TEST(Medit, ADirectoryReadsAsAnEmptyFile) {
  const auto d = tmpPath("dir.mesh");
  std::filesystem::create_directories(d);
  expectInputError([&] { io::readMesh(d); }, {"dir.mesh:1:", "empty file"});
  std::filesystem::remove(d);
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
  const Mesh2 m = io::parseMesh(
      "meshversionformatted 2 # c\ndimension 2\nVERTICES 3\n0 0 0\n1 0 0\n0 1 0 # v3\ntriangles 1 1 2 3 4\nend\n",
      "x.mesh");
  EXPECT_EQ(m.numTriangles(), 1);
  EXPECT_EQ(m.triangleRefs[0], 4);
}

TEST(Medit, BadFilesNameFileAndLine) {
  expectInputError([] { io::readMesh(kData + "/truncated.mesh"); }, {"truncated.mesh:7:", "unexpected end of file"});
  expectInputError([] { io::readMesh(kData + "/nan.mesh"); }, {"nan.mesh:7:", "not finite"});
  expectInputError([] { io::readMesh(kData + "/bad_index.mesh"); },
                   {"bad_index.mesh:10:", "vertex index 7 out of range [1, 3]"});
  expectInputError([] { io::readMesh(kData + "/empty.mesh"); }, {"empty.mesh:1:", "empty file"});
  expectInputError([] { io::readMesh(kData + "/garbage.mesh"); }, {"garbage.mesh:5:"});
  expectInputError([] { io::readMesh(kData + "/does-not-exist.mesh"); }, {"does-not-exist.mesh", "cannot open"});
  expectInputError([] { io::readSol(kData + "/nonspd.sol", 5); },
                   {"nonspd.sol:13: tensor of vertex 5 (1, 2, 1) is not positive definite"});
  expectInputError([] { io::readSol(kData + "/negative-size.sol", 5); },
                   {"negative-size.sol:8:", "size of vertex 3 is -0.2"});
  expectInputError([] { io::readSol(kData + "/mismatch.sol", 5); },
                   {"mismatch.sol:4:", "3 solution values but the mesh has 5 vertices"});
  expectInputError([] { io::readSol(kData + "/square.mesh"); }, {"square.mesh", "no SolAtVertices"});
}

TEST(Medit, HugeCountDoesNotAllocate) {
  expectInputError(
      [] { io::parseMesh("MeshVersionFormatted 2\nDimension 2\nVertices\n2000000000\n0 0 0\n", "huge.mesh"); },
      {"huge.mesh:4:", "more than the file can hold"});
}

TEST(Medit, ScalarSizeWithoutARepresentableTensorNamesTheLine) {
  // 1/h² overflows (h = 1e-200) or h² does (h = 1e200): no SPD tensor. The error must name
  // the file and line, not only Metric2's "metric: sizes (...) give a tensor that is not numerically SPD".
  for (const char* h : {"1e-200", "1e200"})
    expectInputError(
        [h] {
          io::parseSol(std::string("MeshVersionFormatted 2\nSolAtVertices\n2\n1 1\n0.5\n") + h + "\nEnd\n", "tiny.sol");
        },
        {"tiny.sol:6: size of vertex 2 is", "not representable"});
}

// Fuzz-like: every prefix and random byte corruptions of valid files either parse or throw
// InputError (never crash, never another exception type).
TEST(Medit, TruncatedAndGarbledInputsOnlyThrowInputError) {
  const std::string mesh =
      "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n"
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
        if (isMesh)
          io::parseMesh(in, "f.mesh");
        else
          io::parseSol(in, "f.sol");
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
  EXPECT_THROW(io::parseMesh("MeshVersionFormatted 1\nDimension 2\nIdentifier\n\"never closed\n", "q.mesh"),
               InputError);
}

TEST(Medit, Dimension3PlanarTensorSol) {
  const auto r =
      io::parseSol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 3\n4 1 0 9 0 1\nEnd\n", "d3.sol");
  EXPECT_EQ(r[0].m11(), 4);
  EXPECT_EQ(r[0].m12(), 1);
  EXPECT_EQ(r[0].m22(), 9);
  EXPECT_THROW(
      io::parseSol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 3\n4 1 0.5 9 0 1\nEnd\n", "d3.sol"),
      InputError);
}

// --- Files as tools write them: partial or repeated Edges, subdomains, features, multi-field .sol.

/// Unit square split into 4 triangles around its centre (vertex 5); triangle refs 1 1 2 2.
static std::string squareWith(const std::string& edges, const std::string& extra = "",
                              const std::string& triangles = "4\n1 2 5 1\n2 3 5 1\n3 4 5 2\n4 1 5 2\n") {
  return "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n" + edges +
         "Triangles\n" + triangles + extra + "End\n";
}

TEST(Medit, PartialEdgesAreCompletedWithRefZero) {
  const io::MeshFile f = io::parseMeshFile(squareWith("Edges\n1\n2 1 7\n"), "partial.mesh");
  const Mesh2& m = f.mesh;
  ASSERT_EQ(m.boundaryEdges.size(), 4u);
  EXPECT_EQ(m.boundaryEdges[0].ref, 7);
  EXPECT_EQ(m.boundaryEdges[0].a, 0);  // reoriented: domain on the left
  for (std::size_t e = 1; e < 4; ++e) EXPECT_EQ(m.boundaryEdges[e].ref, 0);
  // triangles 2-3-5 (ref 1) and 3-4-5 (ref 2) meet on 3-5; 1-5 separates refs 2 and 1
  EXPECT_EQ(m.interfaceEdges.size(), 2u);
  EXPECT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
  ASSERT_EQ(f.warnings.size(), 2u);
  EXPECT_NE(f.warnings[0].find("partial.mesh: 3 boundary edges not in Edges"), std::string::npos) << f.warnings[0];
  EXPECT_NE(f.warnings[1].find("2 edges between subdomains"), std::string::npos) << f.warnings[1];
  // No Edges section at all: every boundary edge derived.
  const io::MeshFile g = io::parseMeshFile(squareWith(""), "none.mesh");
  EXPECT_EQ(g.mesh.boundaryEdges.size(), 4u);
  EXPECT_TRUE(g.mesh.validate(1.0).ok) << g.mesh.validate().firstProblem;
}

TEST(Medit, RepeatedEdgesAndTrianglesAreMergedWithAWarning) {
  const std::string edges = "Edges\n6\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n2 1 9\n3 4 3\n";
  const std::string tris = "5\n1 2 5 1\n2 3 5 1\n3 4 5 2\n4 1 5 2\n5 3 2 1\n";
  const io::MeshFile f = io::parseMeshFile(squareWith(edges, "", tris), "dup.mesh");
  EXPECT_EQ(f.mesh.numTriangles(), 4);
  ASSERT_EQ(f.mesh.boundaryEdges.size(), 4u);
  EXPECT_EQ(f.mesh.boundaryEdges[0].ref, 1);  // the first listing's ref
  EXPECT_TRUE(f.mesh.validate(1.0).ok) << f.mesh.validate().firstProblem;
  std::string all;
  for (const auto& w : f.warnings) all += w + "\n";
  EXPECT_NE(all.find("dup.mesh: 1 repeated triangle merged"), std::string::npos) << all;
  EXPECT_NE(all.find("dup.mesh: 2 repeated edges merged"), std::string::npos) << all;
}

TEST(Medit, InteriorEdgesInEdgesAreInterfaceEdges) {
  // Listed interior edges: 1-5 (ref 11) between triangles 4-1-5 (ref 2) and 1-2-5 (ref 1), and
  // 2-5 (ref 12) between two ref-1 triangles (a marked line inside one subdomain).
  const io::MeshFile f = io::parseMeshFile(squareWith("Edges\n2\n1 5 11\n2 5 12\n"), "itf.mesh");
  const Mesh2& m = f.mesh;
  ASSERT_EQ(m.interfaceEdges.size(), 3u);  // 1-5, 2-5 listed; 3-5 derived
  EXPECT_EQ(m.interfaceEdges[0].ref, 11);
  EXPECT_EQ(m.interfaceEdges[1].ref, 12);
  EXPECT_EQ(m.interfaceEdges[2].ref, 0);
  EXPECT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
  // Round trip keeps them.
  const auto p = tmpPath("itf.mesh");
  io::writeMesh(p, m);
  const io::MeshFile r = io::readMeshFile(p);
  EXPECT_EQ(r.mesh.interfaceEdges.size(), 3u);
  EXPECT_TRUE(r.warnings.empty());
  std::filesystem::remove(p);
}

TEST(Medit, EdgeInNoTriangleIsAnError) {
  expectInputError([] { io::parseMeshFile(squareWith("Edges\n1\n1 3 1\n", "", "2\n1 2 5 1\n2 3 5 1\n"), "x.mesh"); },
                   {"x.mesh", "edge (1, 3)", "no triangle"});
}

TEST(Medit, FeatureSectionsAreReadAndWritten) {
  const std::string edges = "Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n";
  const std::string extra = "Corners\n2\n1 3\nRequiredVertices\n1\n5\nRequiredEdges\n1\n2\nRidges\n2\n3 4\n";
  const io::MeshFile f = io::parseMeshFile(squareWith(edges, extra), "feat.mesh");
  const Mesh2& m = f.mesh;
  EXPECT_EQ(m.corners, (std::vector<int>{0, 2}));
  EXPECT_EQ(m.requiredVertices, (std::vector<int>{4}));
  ASSERT_EQ(m.requiredEdges.size(), 1u);
  EXPECT_EQ(m.requiredEdges[0], (std::array<int, 2>{1, 2}));
  ASSERT_EQ(m.ridges.size(), 2u);
  EXPECT_EQ(m.ridges[1], (std::array<int, 2>{3, 0}));
  EXPECT_TRUE(m.validate(1.0).ok) << m.validate().firstProblem;
  const auto p = tmpPath("feat.mesh");
  io::writeMesh(p, m);
  const Mesh2 r = io::readMesh(p);
  EXPECT_EQ(r.corners, m.corners);
  EXPECT_EQ(r.requiredVertices, m.requiredVertices);
  EXPECT_EQ(r.requiredEdges, m.requiredEdges);
  EXPECT_EQ(r.ridges, m.ridges);
  std::filesystem::remove(p);
  expectInputError([&] { io::parseMeshFile(squareWith(edges, "Corners\n1\n9\n"), "c.mesh"); },
                   {"c.mesh:", "Corners entry 1: index 9 out of range [1, 5]"});
  expectInputError([&] { io::parseMeshFile(squareWith(edges, "Ridges\n1\n5\n"), "r.mesh"); },
                   {"r.mesh:", "Ridges names edge 5 but Edges has 4"});
}

TEST(Medit, ValidateKnowsInterfaceEdges) {
  Mesh2 m = io::parseMesh(squareWith("Edges\n1\n1 5 3\n"), "v.mesh");
  ASSERT_TRUE(m.validate().ok) << m.validate().firstProblem;
  Mesh2 missing = m;
  missing.interfaceEdges.pop_back();  // a subdomain change not listed
  EXPECT_NE(missing.validate().firstProblem.find("separates subdomains"), std::string::npos)
      << missing.validate().firstProblem;
  Mesh2 onBoundary = m;
  onBoundary.interfaceEdges.push_back({0, 1, 5});
  EXPECT_NE(onBoundary.validate().firstProblem.find("lies in one triangle"), std::string::npos)
      << onBoundary.validate().firstProblem;
  Mesh2 twice = m;
  twice.interfaceEdges.push_back({twice.interfaceEdges[0].b, twice.interfaceEdges[0].a, 1});
  EXPECT_NE(twice.validate().firstProblem.find("listed twice"), std::string::npos) << twice.validate().firstProblem;
  Mesh2 badCorner = m;
  badCorner.corners = {7};
  EXPECT_FALSE(badCorner.validate().ok);
  Mesh2 badRidge = m;
  badRidge.ridges = {{0, 2}};  // a diagonal that is no edge
  EXPECT_NE(badRidge.validate().firstProblem.find("ridge (0, 2) is not an edge"), std::string::npos);
}

TEST(Medit, SolFieldIsChosenAmongSeveral) {
  // fields: scalar, vector, tensor, scalar (as the naca example of MMG: types 1 2 ... 3)
  const std::string sol =
      "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n4 1 2 3 1\n"
      "0.5  7 8  4 0 9  0.25\n"
      "0.5  7 8  1 0 1  0.25\nEnd\n";
  const auto tensor = io::parseSol(sol, "m.sol");  // the one tensor field by default
  ASSERT_EQ(tensor.size(), 2u);
  EXPECT_EQ(tensor[0].m11(), 4);
  EXPECT_EQ(tensor[0].m22(), 9);
  const auto size = io::parseSol(sol, "m.sol", 2, 4);
  EXPECT_DOUBLE_EQ(size[0].m11(), 16);  // h = 0.25
  const auto first = io::parseSol(sol, "m.sol", 2, 1);
  EXPECT_DOUBLE_EQ(first[0].m11(), 4);  // h = 0.5
  expectInputError([&] { io::parseSol(sol, "m.sol", 2, 2); }, {"m.sol:", "field 2 has type 2"});
  expectInputError([&] { io::parseSol(sol, "m.sol", 2, 5); }, {"m.sol:", "field 5 asked for", "4 solution fields"});
}

TEST(Medit, BoundaryOnlyFileKeepsItsEdges) {
  const std::string text =
      "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "Edges\n5\n1 2 1\n2 3 1\n3 4 2\n4 1 2\n2 1 1\nEnd\n";
  const io::MeshFile f = io::parseMeshFile(text, "b.mesh");
  EXPECT_EQ(f.mesh.numTriangles(), 0);
  EXPECT_EQ(f.mesh.boundaryEdges.size(), 4u);
  ASSERT_EQ(f.warnings.size(), 1u);
}
