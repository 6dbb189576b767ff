// mesher/improve.hpp: the quality post-pass — a pushed interior vertex is put back (q min
// raised, mesh valid, boundary and vertex count kept, moved metrics re-evaluated); boundary
// vertices never move; swaps only across strictly convex quadrilaterals; a cluster of two
// nodes that no move can spread is collapsed (and only then fixed); determinism; q min never
// decreases and the boundary stays on randomly perturbed meshes; option errors; meshDomain's
// wiring (metric vector in step with the vertices after collapses).
#include "ablmg/mesher/improve.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

int gridId(int n, int i, int j) { return j * (n + 1) + i; }

/// The unit square as n × n cells, each split by its (i, j)–(i+1, j+1) diagonal into two
/// right isosceles triangles (q = √3/2 in the identity metric); boundary tags 1–4.
Mesh2 gridMesh(int n) {
  Mesh2 m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(double(i) / n, double(j) / n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v00 = gridId(n, i, j), v10 = gridId(n, i + 1, j), v01 = gridId(n, i, j + 1),
                v11 = gridId(n, i + 1, j + 1);
      m.triangles.push_back({v00, v10, v11});
      m.triangles.push_back({v00, v11, v01});
    }
  for (int i = 0; i < n; ++i) {
    m.boundaryEdges.push_back({gridId(n, i, 0), gridId(n, i + 1, 0), 1});
    m.boundaryEdges.push_back({gridId(n, n, i), gridId(n, n, i + 1), 2});
    m.boundaryEdges.push_back({gridId(n, i + 1, n), gridId(n, i, n), 3});
    m.boundaryEdges.push_back({gridId(n, 0, i + 1), gridId(n, 0, i), 4});
  }
  return m;
}

std::vector<Metric2> metricsAtVertices(const Mesh2& mesh, const MetricField& field) {
  std::vector<Metric2> m;
  for (const Vec2& x : mesh.vertices) m.push_back(field.at(x));
  return m;
}

std::vector<char> boundaryFlags(const Mesh2& mesh) {
  std::vector<char> on(mesh.vertices.size(), 0);
  for (const auto& e : mesh.boundaryEdges) on[std::size_t(e.a)] = on[std::size_t(e.b)] = 1;
  return on;
}

double minQuality(const Mesh2& mesh, const std::vector<Metric2>& metrics) {
  const auto q = elementQualities(mesh, metrics);
  return *std::min_element(q.begin(), q.end());
}

/// The same boundary edges in the same order, with the same refs and bit-identical end points
/// (ids may differ: a collapse renumbers the vertices after the one it removes).
bool sameBoundary(const Mesh2& a, const Mesh2& b) {
  if (a.boundaryEdges.size() != b.boundaryEdges.size()) return false;
  for (std::size_t k = 0; k < a.boundaryEdges.size(); ++k) {
    const auto &x = a.boundaryEdges[k], &y = b.boundaryEdges[k];
    if (x.ref != y.ref || a.vertices[std::size_t(x.a)] != b.vertices[std::size_t(y.a)] ||
        a.vertices[std::size_t(x.b)] != b.vertices[std::size_t(y.b)])
      return false;
  }
  const auto onA = boundaryFlags(a), onB = boundaryFlags(b);
  return std::count(onA.begin(), onA.end(), 1) == std::count(onB.begin(), onB.end(), 1);
}

/// Moves each interior vertex of `mesh` by up to `amplitude` per coordinate, keeping every
/// incident triangle strictly counter-clockwise (exact test), so the mesh stays valid.
void perturbInterior(Mesh2& mesh, double amplitude, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  const auto on = boundaryFlags(mesh);
  const auto star = mesh.vertexTriangles();
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 delta(u(rng), u(rng));
    if (on[std::size_t(v)]) continue;
    const Vec2 old = mesh.vertices[std::size_t(v)];
    mesh.vertices[std::size_t(v)] = old + delta;
    for (int k = star.offsets[std::size_t(v)]; k < star.offsets[std::size_t(v) + 1]; ++k) {
      const auto& t = mesh.triangles[std::size_t(star.ids[std::size_t(k)])];
      if (orient2d(mesh.vertices[std::size_t(t[0])], mesh.vertices[std::size_t(t[1])],
                   mesh.vertices[std::size_t(t[2])]) <= 0) {
        mesh.vertices[std::size_t(v)] = old;
        break;
      }
    }
  }
}

/// Two triangles t = (p, a, b), u = (q, b, a) sharing the diagonal a–b; all four vertices are
/// on the boundary p → a → q → b → p (nothing can move: only a swap can change the mesh).
Mesh2 twoTriangles(Vec2 p, Vec2 a, Vec2 q, Vec2 b) {
  Mesh2 m;
  m.vertices = {p, a, q, b};
  m.triangles = {{0, 1, 3}, {2, 3, 1}};
  m.boundaryEdges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return m;
}

bool hasEdge(const Mesh2& m, int a, int b) {
  for (const auto& e : m.edges())
    if (e[0] == std::min(a, b) && e[1] == std::max(a, b)) return true;
  return false;
}

/// A regular hexagon of unit side (boundary v0…v5, v_k at 60k°) with two interior vertices
/// a = (−ε, 0), b = (ε, 0) on a short edge where one centre vertex belongs: b is joined to
/// v5, v0, v1, v2, a to v2, v3, v4, v5. In the identity metric the best mesh is the six
/// equilateral triangles around one centre vertex; with two vertices no placement comes close.
Mesh2 hexagonWithTwoCentres(double eps) {
  Mesh2 m;
  for (int k = 0; k < 6; ++k)
    m.vertices.emplace_back(std::cos(k * std::numbers::pi / 3), std::sin(k * std::numbers::pi / 3));
  m.vertices.emplace_back(-eps, 0);  // a = 6
  m.vertices.emplace_back(eps, 0);   // b = 7
  const int a = 6, b = 7;
  m.triangles = {{b, 5, 0}, {b, 0, 1}, {b, 1, 2}, {b, 2, a}, {b, a, 5}, {a, 2, 3}, {a, 3, 4}, {a, 4, 5}};
  for (int k = 0; k < 6; ++k) m.boundaryEdges.push_back({k, (k + 1) % 6, 1 + k});
  return m;
}

}  // namespace

TEST(Improve, PushedInteriorVertexIsPutBack) {
  const int n = 6;
  Mesh2 mesh = gridMesh(n);
  const ConstantMetricField field(Metric2::isotropic(1.0 / n));
  // Vertex (3, 3) almost onto the ring side (4, 3)–(4, 4) of its star: one sliver.
  const int v = gridId(n, 3, 3);
  mesh.vertices[std::size_t(v)] = Vec2(4.0 / n - 1e-3, 3.5 / n);
  mesh.requireValid("input", 1.0);
  std::vector<Metric2> metrics = metricsAtVertices(mesh, field);
  const Mesh2 before = mesh;
  ASSERT_LT(minQuality(mesh, metrics), 0.05);

  const ImproveStats s = improveQuality(mesh, metrics, field);
  mesh.requireValid("improved", 1.0);
  EXPECT_GT(minQuality(mesh, metrics), 0.8);  // the grid's own q is √3/2 ≈ 0.866
  EXPECT_EQ(mesh.numVertices(), before.numVertices());
  EXPECT_EQ(mesh.numTriangles(), before.numTriangles());
  EXPECT_TRUE(sameBoundary(mesh, before));
  EXPECT_GE(s.badBefore, 1);
  EXPECT_EQ(s.badAfter, 0);
  EXPECT_GE(s.moves, 1);
  EXPECT_GE(s.passes, 1);
  EXPECT_LE(s.passes, ImproveOptions{}.maxPasses);
  EXPECT_LT(s.qMinBefore, 0.05);
  EXPECT_DOUBLE_EQ(s.qMinAfter, minQuality(mesh, metrics));
  EXPECT_NE(mesh.vertices[std::size_t(v)], before.vertices[std::size_t(v)]);
}

TEST(Improve, MovedVerticesGetTheFieldsMetric) {
  const int n = 8;
  Mesh2 mesh = gridMesh(n);
  const AnalyticMetricField field(AnalyticMetricField::Form::Sizes, "0.1 + 0.1*x", "0.05 + 0.05*y", "0.3");
  for (int j = 2; j <= 6; j += 2) mesh.vertices[std::size_t(gridId(n, 4, j))] = Vec2(5.0 / n - 2e-3, (j + 0.5) / n);
  mesh.requireValid("input", 1.0);
  std::vector<Metric2> metrics = metricsAtVertices(mesh, field);
  const Mesh2 before = mesh;
  const std::vector<Metric2> metricsBefore = metrics;
  const ImproveStats s = improveQuality(mesh, metrics, field);
  ASSERT_GE(s.moves, 3);
  EXPECT_GT(s.qMinAfter, s.qMinBefore + 0.3);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Metric2 expected = mesh.vertices[std::size_t(v)] == before.vertices[std::size_t(v)]
                                 ? metricsBefore[std::size_t(v)]
                                 : field.at(mesh.vertices[std::size_t(v)]);
    EXPECT_EQ(metrics[std::size_t(v)].m11(), expected.m11()) << "vertex " << v;
    EXPECT_EQ(metrics[std::size_t(v)].m12(), expected.m12()) << "vertex " << v;
    EXPECT_EQ(metrics[std::size_t(v)].m22(), expected.m22()) << "vertex " << v;
  }
}

TEST(Improve, BoundaryVerticesNeverMove) {
  const int n = 6;
  Mesh2 mesh = gridMesh(n);
  const ConstantMetricField field(Metric2::isotropic(1.0 / n));
  // A boundary vertex slid along the bottom side next to the corner, and the interior vertex
  // above it pushed down: slivers that moving the boundary vertex back would fix best.
  mesh.vertices[std::size_t(gridId(n, 1, 0))] = Vec2(0.01, 0);
  mesh.vertices[std::size_t(gridId(n, 1, 1))] = Vec2(0.02, 0.02);
  mesh.requireValid("input", 1.0);
  std::vector<Metric2> metrics = metricsAtVertices(mesh, field);
  const Mesh2 before = mesh;
  const ImproveStats s = improveQuality(mesh, metrics, field, {.qThreshold = 0.9});
  mesh.requireValid("improved", 1.0);
  EXPECT_TRUE(sameBoundary(mesh, before));
  EXPECT_EQ(mesh.vertices[std::size_t(gridId(n, 1, 0))], Vec2(0.01, 0));
  EXPECT_GT(s.moves, 0);  // not vacuous: interior vertices did move
  EXPECT_GT(s.qMinAfter, s.qMinBefore);
}

TEST(Improve, SwapsAcrossAStrictlyConvexQuadrilateral) {
  // Flat triangles on the long diagonal a–b; the short diagonal p–q is much better.
  Mesh2 mesh = twoTriangles({0, 1}, {-10, 0}, {0, -1}, {10, 0});
  mesh.requireValid("input");
  std::vector<Metric2> metrics(4);
  const ConstantMetricField field{Metric2()};
  const ImproveStats s = improveQuality(mesh, metrics, field);
  mesh.requireValid("improved");
  EXPECT_EQ(s.swaps, 1);
  EXPECT_TRUE(hasEdge(mesh, 0, 2));
  EXPECT_FALSE(hasEdge(mesh, 1, 3));
  EXPECT_GT(s.qMinAfter, s.qMinBefore);
}

TEST(Improve, NoSwapAcrossAReflexOrFlatCorner) {
  const ConstantMetricField field{Metric2()};
  // Reflex at b: the quadrilateral p, a, q, b is not convex (q b p turns clockwise).
  // Flat at a: p, a, q exactly collinear (integers: the exact predicate says 0).
  for (const auto& quad : {std::array<Vec2, 4>{Vec2(0, 1), Vec2(-10, 0), Vec2(15, -0.2), Vec2(10, 0)},
                           std::array<Vec2, 4>{Vec2(0, 1), Vec2(-10, 0), Vec2(-20, -1), Vec2(10, 0)}}) {
    Mesh2 mesh = twoTriangles(quad[0], quad[1], quad[2], quad[3]);
    mesh.requireValid("input");
    ASSERT_LE(orient2d(quad[0], quad[1], quad[2]) * orient2d(quad[2], quad[3], quad[0]), 0);
    const Mesh2 before = mesh;
    std::vector<Metric2> metrics(4);
    const ImproveStats s = improveQuality(mesh, metrics, field, {.qThreshold = 1.0});
    EXPECT_GT(s.badBefore, 0);  // not vacuous: the triangles are bad
    EXPECT_EQ(s.swaps, 0);
    EXPECT_EQ(s.moves, 0);
    EXPECT_EQ(mesh.triangles, before.triangles);
    EXPECT_EQ(mesh.vertices, before.vertices);
  }
}

TEST(Improve, SameInputSameOutput) {
  const int n = 12;
  const AnalyticMetricField field(AnalyticMetricField::Form::Sizes, "0.08 + 0.1*x", "0.04", "0.5 + y");
  Mesh2 input = gridMesh(n);
  perturbInterior(input, 0.45 / n, 7);
  input.requireValid("input", 1.0);
  const std::vector<Metric2> inputMetrics = metricsAtVertices(input, field);

  Mesh2 a = input, b = input;
  std::vector<Metric2> ma = inputMetrics, mb = inputMetrics;
  const ImproveStats sa = improveQuality(a, ma, field), sb = improveQuality(b, mb, field);
  ASSERT_GT(sa.swaps + sa.moves, 0);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  for (std::size_t v = 0; v < ma.size(); ++v) {
    EXPECT_EQ(ma[v].m11(), mb[v].m11());
    EXPECT_EQ(ma[v].m12(), mb[v].m12());
    EXPECT_EQ(ma[v].m22(), mb[v].m22());
  }
  EXPECT_EQ(sa.swaps, sb.swaps);
  EXPECT_EQ(sa.moves, sb.moves);
  EXPECT_EQ(sa.collapses, sb.collapses);
  EXPECT_EQ(sa.passes, sb.passes);
  EXPECT_EQ(sa.qMinAfter, sb.qMinAfter);
}

TEST(Improve, CollapseMergesTwoNodesNoMoveCanSpread) {
  const ConstantMetricField field{Metric2()};
  const Mesh2 input = hexagonWithTwoCentres(1e-3);
  const double area = input.area();
  input.requireValid("input", area);
  const std::vector<Metric2> inputMetrics(8);
  ASSERT_LT(minQuality(input, inputMetrics), 0.01);

  // Moves and swaps alone cannot reach the threshold: two nodes where one belongs.
  Mesh2 moved = input;
  std::vector<Metric2> movedMetrics = inputMetrics;
  const ImproveStats sm = improveQuality(moved, movedMetrics, field, {.qThreshold = 0.95, .collapseEdges = false});
  EXPECT_EQ(sm.collapses, 0);
  EXPECT_GT(sm.moves, 0);
  EXPECT_LT(sm.qMinAfter, 0.9);

  // The collapse merges a and b at the centre: six equilateral triangles.
  Mesh2 mesh = input;
  std::vector<Metric2> metrics = inputMetrics;
  const ImproveStats s = improveQuality(mesh, metrics, field, {.qThreshold = 0.95});
  mesh.requireValid("improved", area);
  EXPECT_EQ(s.collapses, 1);
  EXPECT_EQ(mesh.numVertices(), 7);
  EXPECT_EQ(mesh.numTriangles(), 6);
  ASSERT_EQ(metrics.size(), 7u);
  EXPECT_TRUE(sameBoundary(mesh, input));
  for (int k = 0; k < 6; ++k) EXPECT_EQ(mesh.vertices[std::size_t(k)], input.vertices[std::size_t(k)]);  // ids kept
  EXPECT_GT(s.qMinAfter, 0.99);
  EXPECT_GT(s.qMinAfter, sm.qMinAfter + 0.1);
  EXPECT_DOUBLE_EQ(s.qMinAfter, minQuality(mesh, metrics));
  EXPECT_LT(mesh.vertices[6].norm(), 0.02);
}

TEST(Improve, NoCollapseOfAnEdgeWithABoundaryEnd) {
  // Interior vertex b pushed next to boundary vertex v0: the bad triangles' shortest edge is
  // b–v0, which must not collapse (v0 would move or vanish); a move fixes b instead, exactly
  // as with collapses switched off.
  const ConstantMetricField field{Metric2()};
  Mesh2 mesh = hexagonWithTwoCentres(0.2);
  mesh.vertices[7] = Vec2(0.99, 0.001);
  mesh.requireValid("input", mesh.area());
  std::vector<Metric2> metrics(8);
  const Mesh2 before = mesh;
  Mesh2 noCollapse = mesh;
  std::vector<Metric2> noCollapseMetrics = metrics;
  const ImproveStats s = improveQuality(mesh, metrics, field, {.qThreshold = 0.8, .maxPasses = 1});
  improveQuality(noCollapse, noCollapseMetrics, field, {.qThreshold = 0.8, .maxPasses = 1, .collapseEdges = false});
  mesh.requireValid("improved", before.area());
  EXPECT_LT(s.qMinBefore, 0.05);
  EXPECT_GT(s.moves, 0);
  EXPECT_EQ(s.collapses, 0);
  EXPECT_EQ(mesh.vertices, noCollapse.vertices);
  EXPECT_EQ(mesh.triangles, noCollapse.triangles);
  EXPECT_TRUE(sameBoundary(mesh, before));
  for (int k = 0; k < 6; ++k) EXPECT_EQ(mesh.vertices[std::size_t(k)], before.vertices[std::size_t(k)]);
  EXPECT_GT(s.qMinAfter, s.qMinBefore);
}

TEST(Improve, CollapsesAreDeterministicAndKeepTheMetricInStep) {
  // A perturbed graded grid at a high threshold: many collapses and moves.
  const int n = 16;
  const AnalyticMetricField field(AnalyticMetricField::Form::Sizes, "0.05 + 0.1*x", "0.05 + 0.05*y", "0.3");
  Mesh2 input = gridMesh(n);
  perturbInterior(input, 0.49 / n, 11);
  input.requireValid("input", 1.0);
  const std::vector<Metric2> inputMetrics = metricsAtVertices(input, field);
  Mesh2 a = input, b = input;
  std::vector<Metric2> ma = inputMetrics, mb = inputMetrics;
  const ImproveStats sa = improveQuality(a, ma, field, {.qThreshold = 0.95}),
                     sb = improveQuality(b, mb, field, {.qThreshold = 0.95});
  ASSERT_GT(sa.collapses, 0);
  a.requireValid("improved", 1.0);
  EXPECT_TRUE(sameBoundary(a, input));
  EXPECT_GE(sa.qMinAfter, sa.qMinBefore);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(ma.size(), std::size_t(a.numVertices()));
  for (std::size_t v = 0; v < ma.size(); ++v) {
    EXPECT_EQ(ma[v].m11(), mb[v].m11());
    EXPECT_EQ(ma[v].m12(), mb[v].m12());
    EXPECT_EQ(ma[v].m22(), mb[v].m22());
    // Every vertex carries the field's metric at its (possibly new) position: the input had
    // the field's metric everywhere, moved and merged vertices get field.at(new position).
    const Metric2 expected = field.at(a.vertices[v]);
    EXPECT_NEAR(ma[v].m11(), expected.m11(), 1e-12 * expected.m11()) << "vertex " << v;
    EXPECT_NEAR(ma[v].m22(), expected.m22(), 1e-12 * expected.m22()) << "vertex " << v;
  }
  EXPECT_EQ(sa.collapses, sb.collapses);
  EXPECT_EQ(sa.qMinAfter, sb.qMinAfter);
}

TEST(Improve, RandomPerturbedMeshesStayValidAndNeverGetWorse) {
  long collapses = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const int n = 5 + int(seed % 7);
    const Metric2 m = Metric2::fromSizes((0.5 + u(rng)) / n, (0.2 + 0.8 * u(rng)) / n, 3.14 * u(rng));
    const ConstantMetricField field(m);
    Mesh2 mesh = gridMesh(n);
    perturbInterior(mesh, 0.49 / n, seed);
    mesh.requireValid("input", 1.0);
    std::vector<Metric2> metrics(std::size_t(mesh.numVertices()), m);
    const Mesh2 before = mesh;
    const ImproveStats s =
        improveQuality(mesh, metrics, field, {.qThreshold = 0.5 + 0.5 * u(rng), .maxPasses = 1 + int(seed % 5)});
    const auto v = mesh.validate(1.0, 1e-9);
    ASSERT_TRUE(v.ok) << "seed " << seed << ": " << v.firstProblem;
    EXPECT_TRUE(sameBoundary(mesh, before)) << "seed " << seed;
    EXPECT_EQ(mesh.numVertices(), before.numVertices() - s.collapses) << "seed " << seed;
    EXPECT_EQ(mesh.numTriangles(), before.numTriangles() - 2 * s.collapses) << "seed " << seed;
    ASSERT_EQ(metrics.size(), std::size_t(mesh.numVertices())) << "seed " << seed;
    EXPECT_GE(s.qMinAfter, s.qMinBefore) << "seed " << seed;
    EXPECT_DOUBLE_EQ(s.qMinAfter, minQuality(mesh, metrics)) << "seed " << seed;
    collapses += s.collapses;
  }
  EXPECT_GT(collapses, 0);  // not vacuous: the collapses were exercised
}

TEST(Improve, NothingBelowTheThresholdLeavesTheMeshAlone) {
  Mesh2 mesh = gridMesh(4);
  perturbInterior(mesh, 0.05, 3);
  const ConstantMetricField field(Metric2::isotropic(0.25));
  std::vector<Metric2> metrics = metricsAtVertices(mesh, field);
  const Mesh2 before = mesh;
  const double qMin = minQuality(mesh, metrics);
  const ImproveStats s = improveQuality(mesh, metrics, field, {.qThreshold = qMin});
  EXPECT_EQ(s.badBefore, 0);
  EXPECT_EQ(s.passes, 0);
  EXPECT_EQ(mesh.vertices, before.vertices);
  EXPECT_EQ(mesh.triangles, before.triangles);
  EXPECT_EQ(s.qMinBefore, qMin);
}

TEST(Improve, BadOptionsAndMetricCountAreInputErrors) {
  Mesh2 mesh = gridMesh(2);
  const ConstantMetricField field{Metric2()};
  std::vector<Metric2> metrics(std::size_t(mesh.numVertices()));
  EXPECT_THROW(improveQuality(mesh, metrics, field, {.qThreshold = 0}), InputError);
  EXPECT_THROW(improveQuality(mesh, metrics, field, {.qThreshold = 1.5}), InputError);
  EXPECT_THROW(improveQuality(mesh, metrics, field, {.maxPasses = -1}), InputError);
  EXPECT_THROW(improveQuality(mesh, metrics, field, {.swapMargin = -1}), InputError);
  std::vector<Metric2> tooFew(3);
  EXPECT_THROW(improveQuality(mesh, tooFew, field), InputError);
}

TEST(Improve, MeshDomainRunsItAndReportsIt) {
  const Domain square = Domain::rectangle(0, 0, 1, 1);
  const AnalyticMetricField field(AnalyticMetricField::Form::Sizes, "0.04 + 0.1*abs(x - 0.5)",
                                  "0.02 + 0.05*abs(x - 0.5)", "0.4");
  MeshOptions off, strict;
  off.improve.enabled = false;
  strict.improve.qThreshold = 0.95;  // forces work on a mesh whose q min is ~0.7
  const MeshResult a = meshDomain(square, field, off), b = meshDomain(square, field, strict);
  EXPECT_EQ(a.stats.improve.passes, 0);
  EXPECT_EQ(a.stats.improve.swaps + a.stats.improve.moves, 0);
  b.mesh.requireValid("meshDomain", 1.0);
  const ImproveStats& s = b.stats.improve;
  EXPECT_EQ(b.mesh.numVertices(), a.mesh.numVertices() - s.collapses);
  ASSERT_EQ(b.metric.size(), std::size_t(b.mesh.numVertices()));
  EXPECT_TRUE(sameBoundary(b.mesh, a.mesh));
  EXPECT_GT(s.badBefore, 0);
  EXPECT_GT(s.swaps + s.moves, 0);
  EXPECT_DOUBLE_EQ(s.qMinBefore, minQuality(a.mesh, a.metric));
  EXPECT_DOUBLE_EQ(s.qMinAfter, minQuality(b.mesh, b.metric));
  EXPECT_GT(s.qMinAfter, s.qMinBefore);
  // The returned metric is the field's at every (possibly moved) vertex.
  for (int v = 0; v < b.mesh.numVertices(); v += 7)
    EXPECT_NEAR(b.metric[std::size_t(v)].m11(), field.at(b.mesh.vertices[std::size_t(v)]).m11(),
                1e-9 * b.metric[std::size_t(v)].m11());
}
