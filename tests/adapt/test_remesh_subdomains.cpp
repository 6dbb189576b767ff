// Mirrors the subdomain part of adapt/remesh.hpp (remeshSubdomains): meshes with several
// triangle refs and interface edges, from our own generator and as FreeFem++ and gmsh write them
// (tests/data/make_multiregion.sh). Checked: the output is valid, every triangle keeps the ref
// of the input subdomain it lies in, every input interface edge is covered by a chain of output
// interface edges, each subdomain's area is kept to round-off on polygons, repeated remeshing of
// a curved interface does not drift, corners and required entities stay, bad inputs are errors.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/remesh.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

using namespace ablmg;
using namespace ablmg::adapt;
static const std::string kData = ABLMG_TEST_DATA;

namespace {

/// n×n grid of the unit square, two triangles per cell; the ref of a cell from its centre:
/// 1 left half, 2 bottom right, 3 top right (interfaces x = 0.5 and y = 0.5 for x > 0.5).
/// Written as medit text without Edges, so the reader derives boundary and interface edges.
Mesh2 threeRegionSquare(int n) {
  std::ostringstream os;
  os << "MeshVersionFormatted 2\nDimension 2\nVertices\n" << (n + 1) * (n + 1) << "\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) os << double(i) / n << " " << double(j) / n << " 0\n";
  os << "Triangles\n" << 2 * n * n << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
      const double x = (i + 0.5) / n, y = (j + 0.5) / n;
      const int ref = x < 0.5 ? 1 : y < 0.5 ? 2 : 3;
      os << a << " " << b << " " << c << " " << ref << "\n" << a << " " << c << " " << d << " " << ref << "\n";
    }
  os << "End\n";
  return io::parseMesh(os.str(), "three.mesh");
}

std::map<int, double> areaByRef(const Mesh2& m) {
  std::map<int, double> a;
  for (int t = 0; t < m.numTriangles(); ++t) a[m.triangleRefs[std::size_t(t)]] += m.triangleArea(t);
  return a;
}

/// The ref of the input triangle containing p (brute force; −1 if none).
int refAt(const Mesh2& m, const Vec2& p) {
  for (int t = 0; t < m.numTriangles(); ++t) {
    const auto& tr = m.triangles[std::size_t(t)];
    if (orient2d(m.vertices[tr[0]], m.vertices[tr[1]], p) >= 0 &&
        orient2d(m.vertices[tr[1]], m.vertices[tr[2]], p) >= 0 &&
        orient2d(m.vertices[tr[2]], m.vertices[tr[0]], p) >= 0)
      return m.triangleRefs[std::size_t(t)];
  }
  return -1;
}

/// Every input interface edge ab is covered exactly once by output interface edges on its
/// line: their overlaps with ab add up to |ab| (to round-off), so on a polygonal interface
/// each input edge lies on a chain of output edges, and no two output edges overlap.
void expectInterfacesCovered(const Mesh2& in, const Mesh2& out) {
  const std::vector<double> covered = adapt::interfaceCoverage(in, out);
  ASSERT_EQ(covered.size(), in.interfaceEdges.size());
  for (std::size_t i = 0; i < covered.size(); ++i) {
    const auto& e = in.interfaceEdges[i];
    const double len = (in.vertices[std::size_t(e.b)] - in.vertices[std::size_t(e.a)]).norm();
    EXPECT_NEAR(covered[i], len, 1e-12 * len) << "input interface edge (" << e.a << ", " << e.b << ")";
  }
}

/// Every output triangle lies in the input subdomain of its ref (tested at its centroid).
void expectRefsWhereTheyWere(const Mesh2& in, const Mesh2& out) {
  long wrong = 0;
  for (int t = 0; t < out.numTriangles(); ++t) {
    const auto& tr = out.triangles[std::size_t(t)];
    const Vec2 c = (out.vertices[tr[0]] + out.vertices[tr[1]] + out.vertices[tr[2]]) / 3;
    const int r = refAt(in, c);
    if (r >= 0 && r != out.triangleRefs[std::size_t(t)]) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
}

std::vector<Metric2> sizes(const Mesh2& m, double h) {
  return std::vector<Metric2>(m.vertices.size(), Metric2::isotropic(h));
}

}  // namespace

TEST(RemeshSubdomains, PolygonalSubdomainsKeepAreasRefsAndInterfaces) {
  const Mesh2 in = threeRegionSquare(8);
  ASSERT_TRUE(in.validate(1.0).ok) << in.validate().firstProblem;
  ASSERT_TRUE(needsSubdomains(in));
  // graded anisotropic metric: finer near the T junction (0.5, 0.5)
  std::vector<Metric2> metric;
  for (const Vec2& p : in.vertices) {
    const double h = 0.02 + 0.1 * (p - Vec2(0.5, 0.5)).norm();
    metric.push_back(Metric2::fromSizes(h, 2 * h, 0.3));
  }
  RemeshOptions o;
  const RemeshResult r = remesh(in, metric, o);
  ASSERT_TRUE(r.mesh.validate(1.0, 1e-12).ok) << r.mesh.validate().firstProblem;
  EXPECT_GT(r.mesh.numVertices(), 150);
  const auto a0 = areaByRef(in), a1 = areaByRef(r.mesh);
  ASSERT_EQ(a1.size(), 3u);
  for (const auto& [ref, a] : a0) EXPECT_NEAR(a1.at(ref), a, 1e-13) << "subdomain " << ref;
  expectInterfacesCovered(in, r.mesh);
  expectRefsWhereTheyWere(in, r.mesh);
  // the T junction and the interface ends on the boundary are vertices of the output
  for (const Vec2& p : {Vec2(0.5, 0.5), Vec2(0.5, 0), Vec2(0.5, 1), Vec2(1, 0.5)}) {
    bool found = false;
    for (const Vec2& v : r.mesh.vertices) found = found || v == p;
    EXPECT_TRUE(found) << p.transpose();
  }
  // boundary refs are the input's (0: the reader added them) and interfaces carry theirs
  for (const auto& e : r.mesh.boundaryEdges) EXPECT_EQ(e.ref, 0);
  EXPECT_EQ(r.metric.size(), r.mesh.vertices.size());
  // deterministic
  const RemeshResult again = remesh(in, metric, o);
  EXPECT_EQ(again.mesh.vertices, r.mesh.vertices);
  EXPECT_EQ(again.mesh.triangles, r.mesh.triangles);
}

TEST(InterfaceCoverage, SumsOverlapsOnTheSameLinePerInputEdge) {
  Mesh2 in;
  in.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)};
  in.interfaceEdges = {{0, 1, 2}, {1, 2, 2}};
  Mesh2 out;
  out.vertices = {Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 0), Vec2(1, 0.25), Vec2(0.5, 0.5)};
  out.interfaceEdges = {{1, 0, 2}, {1, 2, 2}, {2, 3, 2}, {0, 4, 2}};  // the last one is off both lines
  auto c = interfaceCoverage(in, out);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0], 1.0, 1e-15);
  EXPECT_NEAR(c[1], 0.25, 1e-15);
  EXPECT_NEAR(uncoveredInterfaceLength(in, out), 0.75, 1e-15);
  out.interfaceEdges.push_back({0, 1, 2});  // overlaps an edge already there
  c = interfaceCoverage(in, out);
  EXPECT_NEAR(c[0], 1.5, 1e-15);
  EXPECT_NEAR(uncoveredInterfaceLength(in, out), 0.75, 1e-15);
}

TEST(RemeshSubdomains, GmshAndFreeFemMultiRegionFiles) {
  for (const std::string f : {"gmsh_two_regions.mesh", "ff_inclusion.mesh"}) {
    const io::MeshFile file = io::readMeshFile(kData + "/" + f);
    const Mesh2& in = file.mesh;
    ASSERT_TRUE(in.validate().ok) << f << ": " << in.validate().firstProblem;
    EXPECT_FALSE(in.interfaceEdges.empty()) << f;
    const RemeshResult r = remesh(in, sizes(in, 0.04));
    ASSERT_TRUE(r.mesh.validate().ok) << f << ": " << r.mesh.validate().firstProblem;
    const auto a0 = areaByRef(in), a1 = areaByRef(r.mesh);
    ASSERT_EQ(a1.size(), a0.size()) << f;
    expectRefsWhereTheyWere(in, r.mesh);
    if (f == "gmsh_two_regions.mesh") {  // polygonal: areas to round-off, interfaces covered
      for (const auto& [ref, a] : a0) EXPECT_NEAR(a1.at(ref), a, 1e-12) << f << " subdomain " << ref;
      expectInterfacesCovered(in, r.mesh);
    } else {  // the disk: chords of the circle
      for (const auto& [ref, a] : a0) EXPECT_NEAR(a1.at(ref), a, 0.01 * a) << f << " subdomain " << ref;
    }
    // interface refs kept: gmsh writes the interface's curve entities 7 and 8, FreeFem the label 5
    std::set<int> refs;
    for (const auto& e : r.mesh.interfaceEdges) refs.insert(e.ref);
    EXPECT_EQ(refs, (f == "gmsh_two_regions.mesh" ? std::set<int>{7, 8} : std::set<int>{5})) << f;
  }
}

// gmsh's medit output with physical tags (make_multiregion.sh): the unit disk as 4 x 16 chords
// (ref 10) cut along y = 0 (ref 20) into halves 1 (upper) and 3, with the square
// [-0.3, 0.3] x [0.2, 0.6] (ref 30) as subdomain 2 in the upper half. The square is a polygon:
// its area is kept to round-off. The halves' outer boundary is the input's chords; the remesh
// places its vertices on them, so each half loses at most the input's own chord error against
// the exact half disk (the new chords, 2.5 times shorter, cut the input's corners only).
TEST(RemeshSubdomains, GmshThreeSurfacesWithPhysicalTags) {
  const io::MeshFile file = io::readMeshFile(kData + "/gmsh_disk_three.mesh");
  const Mesh2& in = file.mesh;
  ASSERT_TRUE(in.validate().ok) << in.validate().firstProblem;
  const auto a0 = areaByRef(in);
  ASSERT_EQ(a0.size(), 3u);
  EXPECT_NEAR(a0.at(2), 0.24, 1e-12);
  const double pi = std::acos(-1.0);
  const std::map<int, double> chordError{{1, pi / 2 - 0.24 - a0.at(1)}, {3, pi / 2 - a0.at(3)}};
  for (const auto& [ref, err] : chordError) ASSERT_GT(err, 0) << "subdomain " << ref;
  const RemeshResult r = remesh(in, sizes(in, 0.04), RemeshOptions{.name = "gmsh_disk_three.mesh"});
  ASSERT_TRUE(r.mesh.validate().ok) << r.mesh.validate().firstProblem;
  EXPECT_GT(r.mesh.numVertices(), 2 * in.numVertices());
  const auto a1 = areaByRef(r.mesh);
  ASSERT_EQ(a1.size(), 3u);
  EXPECT_NEAR(a1.at(2), a0.at(2), 1e-12);
  for (const auto& [ref, err] : chordError) {
    EXPECT_LE(a1.at(ref), a0.at(ref) + 1e-12) << "subdomain " << ref;  // inside the input's chords
    EXPECT_LE(a0.at(ref) - a1.at(ref), err) << "subdomain " << ref;
  }
  expectInterfacesCovered(in, r.mesh);
  expectRefsWhereTheyWere(in, r.mesh);
  std::set<int> interfaceRefs, boundaryRefs;
  for (const auto& e : r.mesh.interfaceEdges) interfaceRefs.insert(e.ref);
  for (const auto& e : r.mesh.boundaryEdges) boundaryRefs.insert(e.ref);
  EXPECT_EQ(interfaceRefs, (std::set<int>{20, 30}));
  EXPECT_EQ(boundaryRefs, (std::set<int>{10}));
  // the junctions of the cut with the circle and the square's corners are output vertices
  for (const Vec2& p : {Vec2(-1, 0), Vec2(1, 0), Vec2(-0.3, 0.2), Vec2(0.3, 0.2), Vec2(0.3, 0.6), Vec2(-0.3, 0.6)}) {
    bool found = false;
    for (const Vec2& v : r.mesh.vertices) found = found || (v - p).norm() < 1e-12;
    EXPECT_TRUE(found) << p.transpose();
  }
}

// MMG's -nosurf (requireBoundaryEdges): the remesh keeps every boundary and interface edge of
// the input, by coordinates and ref, and adds none, while the inside is meshed to the finer size.
TEST(RemeshSubdomains, RequiredBoundaryEdgesKeepTheBoundaryExactly) {
  Mesh2 in = io::readMesh(kData + "/gmsh_disk_three.mesh");
  requireBoundaryEdges(in);
  ASSERT_EQ(in.requiredEdges.size(), in.boundaryEdges.size() + in.interfaceEdges.size());
  requireBoundaryEdges(in);  // listed once
  ASSERT_EQ(in.requiredEdges.size(), in.boundaryEdges.size() + in.interfaceEdges.size());
  using Key = std::tuple<double, double, double, double, int>;
  const auto keys = [](const Mesh2& m, const std::vector<BoundaryEdge>& edges) {
    std::set<Key> k;
    for (const auto& e : edges) {
      Vec2 p = m.vertices[std::size_t(e.a)], q = m.vertices[std::size_t(e.b)];
      if (std::tie(q.x(), q.y()) < std::tie(p.x(), p.y())) std::swap(p, q);
      k.insert({p.x(), p.y(), q.x(), q.y(), e.ref});
    }
    return k;
  };
  const RemeshResult r = remesh(in, sizes(in, 0.05));
  ASSERT_TRUE(r.mesh.validate().ok) << r.mesh.validate().firstProblem;
  EXPECT_GT(r.mesh.numVertices(), 2 * in.numVertices());
  EXPECT_EQ(keys(r.mesh, r.mesh.boundaryEdges), keys(in, in.boundaryEdges));
  EXPECT_EQ(keys(r.mesh, r.mesh.interfaceEdges), keys(in, in.interfaceEdges));
  const auto a0 = areaByRef(in), a1 = areaByRef(r.mesh);
  for (const auto& [ref, a] : a0) EXPECT_NEAR(a1.at(ref), a, 1e-12) << "subdomain " << ref;
}

// A curved interface in a square (ff_inclusion) and a curved outer boundary with a curved
// interface (ff_disk_inclusion, FreeFem++'s), each remeshed 10 times. The chord error of the
// first remesh is measured per loop: the inclusion's (the interface) and the whole domain's
// (the outer boundary); the outer subdomain lies between the two loops, so its bound is their
// sum (its own area change may be smaller, the two losses having opposite signs there).
TEST(RemeshSubdomains, RepeatedRemeshingOfACurvedInterfaceDoesNotDrift) {
  for (const char* file : {"ff_inclusion.mesh", "ff_disk_inclusion.mesh"}) {
    Mesh2 mesh = io::readMesh(kData + "/" + file);
    const auto a0 = areaByRef(mesh);
    ASSERT_EQ(a0.size(), 2u) << file;
    const int inner = a0.begin()->second < a0.rbegin()->second ? a0.begin()->first : a0.rbegin()->first;
    const double total0 = a0.begin()->second + a0.rbegin()->second;
    std::map<int, double> first, bound;
    for (int cycle = 0; cycle < 10; ++cycle) {
      auto metric = sizes(mesh, 0.05);  // before the move: argument evaluation order is unspecified
      RemeshResult r = remesh(std::move(mesh), std::move(metric));
      ASSERT_TRUE(r.mesh.validate().ok) << file << " cycle " << cycle << ": " << r.mesh.validate().firstProblem;
      mesh = std::move(r.mesh);
      const auto a = areaByRef(mesh);
      if (cycle == 0) {
        first = a;
        const double interfaceChord = std::abs(a.at(inner) - a0.at(inner));
        const double outerChord = std::abs(a.begin()->second + a.rbegin()->second - total0);
        for (const auto& [ref, area] : a) bound[ref] = ref == inner ? interfaceChord : interfaceChord + outerChord;
      }
      for (const auto& [ref, area] : a)
        EXPECT_LE(std::abs(area - first.at(ref)), bound.at(ref) + 1e-12)
            << file << " cycle " << cycle << " subdomain " << ref;
    }
  }
}

TEST(RemeshSubdomains, CornersAndRequiredEntitiesStay) {
  // the unit square (4x4 grid), a corner at (0.5, 0) (a straight boundary point), a required
  // vertex at (0, 0.25), and the required edge (1, 0.5)-(1, 0.75)
  Mesh2 in = threeRegionSquare(4);
  std::fill(in.triangleRefs.begin(), in.triangleRefs.end(), 1);
  in.interfaceEdges.clear();
  const auto id = [&](double x, double y) {
    for (int v = 0; v < in.numVertices(); ++v)
      if (in.vertices[std::size_t(v)] == Vec2(x, y)) return v;
    return -1;
  };
  in.corners = {id(0.5, 0)};
  in.requiredVertices = {id(0, 0.25)};
  in.requiredEdges = {{id(1, 0.5), id(1, 0.75)}};
  ASSERT_TRUE(in.validate(1.0).ok) << in.validate().firstProblem;
  const RemeshResult r = remesh(in, sizes(in, 0.03));
  ASSERT_TRUE(r.mesh.validate(1.0, 1e-12).ok) << r.mesh.validate().firstProblem;
  ASSERT_EQ(r.mesh.corners.size(), 1u);
  EXPECT_EQ(r.mesh.vertices[std::size_t(r.mesh.corners[0])], Vec2(0.5, 0));
  ASSERT_EQ(r.mesh.requiredVertices.size(), 1u);
  EXPECT_EQ(r.mesh.vertices[std::size_t(r.mesh.requiredVertices[0])], Vec2(0, 0.25));
  ASSERT_EQ(r.mesh.requiredEdges.size(), 1u);  // still an edge, though 8 times the size asked
  const auto& e = r.mesh.requiredEdges[0];
  EXPECT_EQ(r.mesh.vertices[std::size_t(e[0])], Vec2(1, 0.5));
  EXPECT_EQ(r.mesh.vertices[std::size_t(e[1])], Vec2(1, 0.75));
  // a required vertex inside the domain is refused, naming it
  Mesh2 inside = in;
  inside.requiredVertices = {id(0.5, 0.5)};
  try {
    remesh(inside, sizes(inside, 0.03), RemeshOptions{.name = "req.mesh"});
    FAIL() << "no exception";
  } catch (const InputError& x) {
    EXPECT_NE(std::string(x.what()).find("req.mesh: required vertex"), std::string::npos) << x.what();
  }
}

TEST(RemeshSubdomains, InterfaceThatSeparatesNothingIsAnError) {
  Mesh2 in = threeRegionSquare(4);
  std::fill(in.triangleRefs.begin(), in.triangleRefs.end(), 1);
  in.interfaceEdges.resize(1);  // one interior edge marked, a dangling line
  ASSERT_TRUE(in.validate().ok) << in.validate().firstProblem;
  try {
    remesh(in, sizes(in, 0.1), RemeshOptions{.name = "line.mesh"});
    FAIL() << "no exception";
  } catch (const InputError& x) {
    EXPECT_NE(std::string(x.what()).find("line.mesh: interface edge"), std::string::npos) << x.what();
    EXPECT_NE(std::string(x.what()).find("separates nothing"), std::string::npos) << x.what();
  }
}

namespace {

/// (−1, 1)² with the slit [0, 1] × {0} (Mitchell's reentrant corner with ω = 2π): a (2m)² grid
/// whose vertices on the slit (x > 0, y = 0) are doubled, the lower cells using the twins; a
/// zero-width gap between two boundary edge chains. Refs from the reader (0). With `shift`, the
/// twins but the last (at the corner (1, 0)) move by shift/m along the slit: the lips then share
/// no point, as when each lip was discretized on its own.
Mesh2 slitSquare(int m, double shift = 0) {
  const int n = 2 * m, nv = (n + 1) * (n + 1);
  std::ostringstream os;
  os << "MeshVersionFormatted 2\nDimension 2\nVertices\n" << nv + m << "\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) os << double(i - m) / m << " " << double(j - m) / m << " 0\n";
  for (int i = m + 1; i <= n; ++i)  // twins, ids nv + (i − m)
    os << (double(i - m) + (i < n ? shift : 0.0)) / m << " 0 0\n";
  const auto id = [&](int i, int j, bool lower) {
    return j == m && i > m && lower ? nv + (i - m) : j * (n + 1) + i + 1;
  };
  os << "Triangles\n" << 2 * n * n << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool lower = j < m;
      const int a = id(i, j, lower), b = id(i + 1, j, lower), c = id(i + 1, j + 1, lower), d = id(i, j + 1, lower);
      os << a << " " << b << " " << c << " 1\n" << a << " " << c << " " << d << " 1\n";
    }
  os << "End\n";
  return io::parseMesh(os.str(), "slit.mesh");
}

}  // namespace

class SlitLips : public ::testing::TestWithParam<double> {};

TEST_P(SlitLips, StayApart) {
  const Mesh2 in = slitSquare(4, GetParam());
  ASSERT_TRUE(in.validate(4.0).ok) << in.validate().firstProblem;
  ASSERT_TRUE(needsSubdomains(in));
  std::vector<Metric2> metric;  // finer towards the tip
  for (const Vec2& p : in.vertices) metric.push_back(Metric2::isotropic(0.02 + 0.1 * p.norm()));
  const RemeshResult r = remesh(in, metric);
  ASSERT_TRUE(r.mesh.validate(4.0, 1e-12).ok) << r.mesh.validate().firstProblem;
  EXPECT_TRUE(r.mesh.interfaceEdges.empty());  // the cut that split the work is not kept
  // no edge crosses the slit (edges on it are the lips), and the two lips share no vertex but
  // the tip: the upper lip runs x-decreasing (domain above, on its left), the lower x-increasing
  long crossing = 0;
  for (const auto& e : r.mesh.edges()) {
    const Vec2 a = r.mesh.vertices[e[0]], b = r.mesh.vertices[e[1]];
    const Vec2 s0(0, 0), s1(1, 0);  // a proper crossing: strictly on both sides, both ways
    crossing += orient2d(a, b, s0) * orient2d(a, b, s1) < 0 && orient2d(s0, s1, a) * orient2d(s0, s1, b) < 0;
  }
  EXPECT_EQ(crossing, 0);
  std::set<int> upper, lower;
  long upperEdges = 0;
  for (const auto& e : r.mesh.boundaryEdges) {
    const Vec2 a = r.mesh.vertices[std::size_t(e.a)], b = r.mesh.vertices[std::size_t(e.b)];
    if (a.y() != 0 || b.y() != 0 || a.x() < 0 || b.x() < 0) continue;
    auto& lip = b.x() < a.x() ? upper : lower;
    lip.insert(e.a);
    lip.insert(e.b);
    upperEdges += b.x() < a.x();
  }
  EXPECT_GE(upperEdges, 5);
  std::vector<int> both;
  std::set_intersection(upper.begin(), upper.end(), lower.begin(), lower.end(), std::back_inserter(both));
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(r.mesh.vertices[std::size_t(both[0])], Vec2(0, 0));
  // the tip is a vertex
  bool tip = false;
  for (const Vec2& v : r.mesh.vertices) tip = tip || v == Vec2(0, 0);
  EXPECT_TRUE(tip);
}

// lips sharing their points, and lips discretized apart (an adapted slit mesh read back)
INSTANTIATE_TEST_SUITE_P(RemeshSubdomains, SlitLips, ::testing::Values(0.0, 0.3));

TEST(RemeshSubdomains, TheLoopsOverloadKeepsSubdomains) {
  // remesh(domain, mesh, metric), the adaptive loop's call: a mesh with subdomains keeps them.
  const Mesh2 in = threeRegionSquare(8);
  const mesher::MeshResult r = remesh(Domain::rectangle(0, 0, 1, 1), in, sizes(in, 0.08));
  ASSERT_TRUE(r.mesh.validate(1.0, 1e-12).ok) << r.mesh.validate().firstProblem;
  const auto a0 = areaByRef(in), a1 = areaByRef(r.mesh);
  ASSERT_EQ(a1.size(), 3u);
  for (const auto& [ref, a] : a0) EXPECT_NEAR(a1.at(ref), a, 1e-13) << "subdomain " << ref;
  expectInterfacesCovered(in, r.mesh);
  expectRefsWhereTheyWere(in, r.mesh);
  EXPECT_EQ(r.metric.size(), r.mesh.vertices.size());
}

// meshDomainWithRegions: tagged polygons inside a domain with a hole, meshed as subdomains.
TEST(RemeshSubdomains, TaggedRegionsOfADomainAreMeshedAsSubdomains) {
  BoundaryLoop outer, hole;
  outer.points = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 1), Vec2(0, 1)};
  hole.points = {Vec2(1.0, 0.4), Vec2(1.1, 0.4), Vec2(1.1, 0.6), Vec2(1.0, 0.6)};
  const Domain domain(outer, {hole});
  const std::vector<TaggedRegion> regions = {{{Vec2(0.2, 0.2), Vec2(0.8, 0.2), Vec2(0.8, 0.8), Vec2(0.2, 0.8)}, 2},
                                             {{Vec2(0.3, 0.3), Vec2(0.5, 0.3), Vec2(0.5, 0.5)}, 4},  // nested in 2
                                             {{Vec2(1.2, 0.3), Vec2(1.8, 0.3), Vec2(1.5, 0.8)}, 3}};
  struct Graded final : MetricField {
    Metric2 at(const Vec2& p) const override { return Metric2::isotropic(0.02 + 0.04 * p.x()); }
  } field;
  const mesher::MeshResult r =
      meshDomainWithRegions(domain, regions, field, mesher::meshPreset(mesher::MeshPreset::Mesh));
  ASSERT_TRUE(r.mesh.validate(2 - 0.02, 1e-12).ok) << r.mesh.validate().firstProblem;
  const auto a = areaByRef(r.mesh);
  ASSERT_EQ(a.size(), 4u);
  EXPECT_NEAR(a.at(4), 0.02, 1e-13);
  EXPECT_NEAR(a.at(2), 0.36 - 0.02, 1e-13);
  EXPECT_NEAR(a.at(3), 0.15, 1e-13);
  EXPECT_NEAR(a.at(0), 2 - 0.02 - 0.36 - 0.15, 1e-12);
  std::map<int, double> interfaceLength;
  for (const auto& e : r.mesh.interfaceEdges)
    interfaceLength[e.ref] += (r.mesh.vertices[std::size_t(e.b)] - r.mesh.vertices[std::size_t(e.a)]).norm();
  EXPECT_NEAR(interfaceLength[2], 2.4, 1e-12);
  EXPECT_NEAR(interfaceLength[4], 0.4 + 0.2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(interfaceLength[3], 0.6 + 2 * std::hypot(0.3, 0.5), 1e-12);
  EXPECT_GT(r.mesh.numVertices(), 1000);
  // bad regions: a tag of 0, a point outside, two that cross
  const auto options = mesher::meshPreset(mesher::MeshPreset::Mesh);
  EXPECT_THROW((void)meshDomainWithRegions(domain, {{regions[2].points, 0}}, field, options), InputError);
  EXPECT_THROW(
      (void)meshDomainWithRegions(domain, {{{Vec2(0.5, 0.5), Vec2(2.5, 0.5), Vec2(0.5, 0.9)}, 2}}, field, options),
      InputError);
  try {
    (void)meshDomainWithRegions(domain, {regions[0], {{Vec2(0.5, 0.5), Vec2(0.9, 0.5), Vec2(0.9, 0.9)}, 5}}, field,
                                options, "cfg.json");
    ADD_FAILURE() << "crossing regions accepted";
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("cross"), std::string::npos) << e.what(); }
}
