// Mirrors adapt/boundary_mesh.hpp and the edges-only path of remesh(): a boundary
// discretization (medit Edges, no Triangles, as MMG takes it) is meshed inside its loops; holes
// and islands by nesting, or interior loops as interfaces; refs, corners and areas kept;
// loops that cross, open chains and branches refused with the vertex or edges named.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/boundary_mesh.hpp"
#include "ablmg/adapt/remesh.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
/// Axis-parallel square loop [x0, x1]², n points a side, counter-clockwise unless `clockwise`.
std::vector<Vec2> square(double x0, double x1, int n, bool clockwise = false) {
  std::vector<Vec2> p;
  const double d = x1 - x0;
  for (int k = 0; k < n; ++k) p.emplace_back(x0 + d * k / n, x0);
  for (int k = 0; k < n; ++k) p.emplace_back(x1, x0 + d * k / n);
  for (int k = 0; k < n; ++k) p.emplace_back(x1 - d * k / n, x1);
  for (int k = 0; k < n; ++k) p.emplace_back(x0, x1 - d * k / n);
  if (clockwise) std::reverse(p.begin(), p.end());
  return p;
}
/// Medit text of the loops (ref per loop: 1 + its index), plus a vertex on no edge at the end.
std::string boundaryFile(const std::vector<std::vector<Vec2>>& loops, bool strayVertex = false) {
  std::ostringstream os;
  os.precision(17);
  std::size_t nv = 0, ne = 0;
  for (const auto& l : loops) nv += l.size(), ne += l.size();
  os << "MeshVersionFormatted 2\nDimension 2\nVertices\n" << nv + (strayVertex ? 1 : 0) << "\n";
  for (const auto& l : loops)
    for (const Vec2& p : l) os << p.x() << " " << p.y() << " 0\n";
  if (strayVertex) os << "0.5 0.5 0\n";
  os << "Edges\n" << ne << "\n";
  std::size_t base = 1;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    for (std::size_t k = 0; k < loops[i].size(); ++k)
      os << base + k << " " << base + (k + 1) % loops[i].size() << " " << i + 1 << "\n";
    base += loops[i].size();
  }
  os << "End\n";
  return os.str();
}
std::map<int, double> areaByRef(const Mesh2& m) {
  std::map<int, double> a;
  for (int t = 0; t < m.numTriangles(); ++t) a[m.triangleRefs[std::size_t(t)]] += m.triangleArea(t);
  return a;
}
std::set<int> boundaryRefs(const Mesh2& m) {
  std::set<int> r;
  for (const auto& e : m.boundaryEdges) r.insert(e.ref);
  return r;
}
}  // namespace

TEST(BoundaryMesh, HoleByNestingAndTheRemeshKeepsAreaAndRefs) {
  // outer loop counter-clockwise, the hole given counter-clockwise too: orientation is not used
  const Mesh2 in = io::parseMesh(boundaryFile({square(0, 1, 5), square(0.3, 0.7, 2)}, true), "hole.mesh");
  ASSERT_EQ(in.numTriangles(), 0);
  const BoundaryTriangulation t = triangulateBoundary(in, "hole.mesh");
  EXPECT_TRUE(t.mesh.validate(1 - 0.16, 1e-13).ok) << t.mesh.validate().firstProblem;
  EXPECT_EQ(t.mesh.numVertices(), 28);  // the stray vertex dropped
  EXPECT_EQ(boundaryRefs(t.mesh), (std::set<int>{1, 2}));
  RemeshOptions o;
  const RemeshResult r = remesh(in, std::vector<Metric2>(in.vertices.size(), Metric2::isotropic(0.05)), o);
  ASSERT_TRUE(r.mesh.validate(1 - 0.16, 1e-12).ok) << r.mesh.validate().firstProblem;
  EXPECT_GT(r.mesh.numVertices(), 300);
  EXPECT_EQ(boundaryRefs(r.mesh), (std::set<int>{1, 2}));
}

TEST(BoundaryMesh, IslandInAHoleIsMeshedAndInteriorLoopsCanBeInterfaces) {
  const auto loops = std::vector<std::vector<Vec2>>{square(0, 1, 4), square(0.2, 0.8, 3, true), square(0.4, 0.6, 1)};
  const Mesh2 in = io::parseMesh(boundaryFile(loops), "island.mesh");
  const BoundaryTriangulation holes = triangulateBoundary(in, "island.mesh");
  const auto a = areaByRef(holes.mesh);
  ASSERT_EQ(a.size(), 2u);  // the ring (ref 1) and the island (ref 3)
  EXPECT_NEAR(a.at(1), 1 - 0.36, 1e-14);
  EXPECT_NEAR(a.at(3), 0.04, 1e-14);
  const BoundaryTriangulation sub = triangulateBoundary(in, "island.mesh", InteriorLoops::Subdomains);
  const auto s = areaByRef(sub.mesh);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s.at(2), 0.36 - 0.04, 1e-14);
  EXPECT_EQ(boundaryRefs(sub.mesh), (std::set<int>{1}));
  EXPECT_EQ(sub.mesh.interfaceEdges.size(), 3 * 4 + 4u);
  // remeshed: three subdomains, areas to round-off (polygons), every interface edge on a chain
  RemeshOptions o;
  o.interiorLoops = InteriorLoops::Subdomains;
  const RemeshResult r = remesh(in, std::vector<Metric2>(in.vertices.size(), Metric2::isotropic(0.04)), o);
  ASSERT_TRUE(r.mesh.validate(1.0, 1e-12).ok) << r.mesh.validate().firstProblem;
  const auto ra = areaByRef(r.mesh);
  ASSERT_EQ(ra.size(), 3u);
  for (const auto& [ref, area] : s) EXPECT_NEAR(ra.at(ref), area, 1e-12) << "subdomain " << ref;
  EXPECT_LT(uncoveredInterfaceLength(sub.mesh, r.mesh), 1e-12);
}

TEST(BoundaryMesh, BadBoundariesAreErrorsNamingTheVertexOrEdges) {
  const auto expectError = [](const std::string& text, const std::string& part) {
    try {
      (void)triangulateBoundary(io::parseMesh(text, "b.mesh"), "b.mesh");
      ADD_FAILURE() << "expected InputError containing '" << part << "'";
    } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what(); }
  };
  // two loops that cross
  expectError(boundaryFile({square(0, 2, 1), square(1, 3, 1)}), "cross");
  // an open chain: the last edge of a loop missing
  std::string open = boundaryFile({square(0, 1, 1)});
  open.replace(open.find("Edges\n4\n"), 8, "Edges\n3\n");
  open.replace(open.find("4 1 1\n"), 6, "");
  expectError(open, "open chain of edges: vertex 1");
  // a branch: a diagonal added
  std::string branch = boundaryFile({square(0, 1, 1)});
  branch.replace(branch.find("Edges\n4\n"), 8, "Edges\n5\n1 3 1\n");
  expectError(branch, "is on 3 edges");
  // no edges at all
  expectError("MeshVersionFormatted 2\nDimension 2\nVertices\n1\n0 0 0\nEnd\n", "neither triangles nor edges");
}
