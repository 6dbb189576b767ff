// Mirrors mesher/slit_domain.hpp (and Domain::withSlit, core/domain.hpp): domains with slits
// mesh to valid meshes whose lips have distinct vertices and that no edge crosses.
#include "ablmg/mesher/slit_domain.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <map>
#include <omp.h>
#include <set>
#include <thread>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// Mesh edges across the straight slit ab whose left lip (seen from a to b) is tagged `left`
/// and right lip `right`: interior edges properly crossing ab, and edges from a lip vertex (not
/// a tip) to the other side. Declared after lipVertices.
int edgesThroughSlit(const Mesh2& m, const Vec2& a, const Vec2& b, int left, int right);

/// The vertices of the boundary edges tagged `tag`.
std::set<int> lipVertices(const Mesh2& m, int tag) {
  std::set<int> out;
  for (const auto& e : m.boundaryEdges)
    if (e.ref == tag) out.insert({e.a, e.b});
  return out;
}

/// The vertices the two lips share (the tips only when the lips are apart).
std::set<Vec2, bool (*)(const Vec2&, const Vec2&)> sharedLipPoints(const Mesh2& m, int left, int right) {
  const auto l = lipVertices(m, left), r = lipVertices(m, right);
  std::set<Vec2, bool (*)(const Vec2&, const Vec2&)> out(
      [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  for (int v : l)
    if (r.count(v)) out.insert(m.vertices[std::size_t(v)]);
  return out;
}

int edgesThroughSlit(const Mesh2& m, const Vec2& a, const Vec2& b, int left, int right) {
  const auto l = lipVertices(m, left), r = lipVertices(m, right);
  int bad = 0;
  for (const auto& e : m.edges()) {
    const Vec2 p = m.vertices[std::size_t(e[0])], q = m.vertices[std::size_t(e[1])];
    if (orient2d(p, q, a) * orient2d(p, q, b) < 0 && orient2d(a, b, p) * orient2d(a, b, q) < 0) ++bad;
    for (int k = 0; k < 2; ++k) {
      const int v = e[k];
      const Vec2 w = m.vertices[std::size_t(e[1 - k])];
      const bool onLeft = l.count(v) && !r.count(v), onRight = r.count(v) && !l.count(v);
      if ((onLeft && orient2d(a, b, w) < 0) || (onRight && orient2d(a, b, w) > 0)) ++bad;
    }
  }
  return bad;
}

}  // namespace

TEST(DomainWithSlit, AttachedSlitIsAZeroWidthGapOfTheOuterLoop) {
  const Domain square = Domain::rectangle(-1, -1, 1, 1);
  EXPECT_FALSE(square.hasSlits());
  const Domain d = square.withSlit({{1, 0}, {0, 0}}, 7, 8);  // from the middle of the right side
  EXPECT_TRUE(d.hasSlits());
  EXPECT_EQ(d.loops().size(), 1u);
  EXPECT_EQ(d.outer().points.size(), 7u);  // 4 corners, the attachment twice, the tip
  EXPECT_NEAR(d.area(), 4.0, 1e-15);
  EXPECT_TRUE(d.contains({0.5, 0}));  // on the slit: boundary, counted inside
  int left = 0, right = 0;
  for (int t : d.outer().tags) left += t == 7, right += t == 8;
  EXPECT_EQ(left, 1);
  EXPECT_EQ(right, 1);
}

TEST(DomainWithSlit, RefusesSlitsThatLeaveTheDomainOrMeetTheBoundary) {
  const Domain square = Domain::rectangle(-1, -1, 1, 1);
  EXPECT_THROW(square.withSlit({{1, 0}, {2, 0}}, 7, 8), InputError);                           // outward
  EXPECT_THROW(square.withSlit({{1, 0}, {-1, 0}}, 7, 8), InputError);                          // across the domain
  EXPECT_THROW(square.withSlit({{0, 0}, {0, 0}}, 7, 8), InputError);                           // repeated point
  EXPECT_THROW(square.withSlit({{1, 0}, {0, 0}, {0.5, 0.5}, {0.5, -0.5}}, 7, 8), InputError);  // self-crossing
  const Domain one = square.withSlit({{1, 0}, {0, 0}}, 7, 8);
  EXPECT_THROW(one.withSlit({{0, 1}, {0, -0.5}}, 5, 6), InputError);  // crosses the first slit
}

TEST(MeshSlitDomain, SquareWithSlitToTheCentreKeepsTheLipsApart) {
  const Domain d = Domain::rectangle(-1, -1, 1, 1).withSlit({{1, 0}, {0, 0}}, 7, 8);
  const ConstantMetricField metric(Metric2::isotropic(0.2));
  const SlitPieces cut = cutAtSlits(d, metric);
  ASSERT_EQ(cut.pieces.size(), 2u);
  EXPECT_NEAR(cut.pieces[0].area() + cut.pieces[1].area(), 4.0, 1e-14);
  ASSERT_EQ(cut.cuts.size(), 1u);
  EXPECT_EQ(cut.cuts[0].front(), Vec2(0, 0));
  EXPECT_EQ(cut.cuts[0].back(), Vec2(-1, 0));
  EXPECT_EQ(cut.cuts[0].size(), 6u);  // length 1 at size 0.2

  const MeshResult r = meshDomain(d, metric);
  EXPECT_TRUE(r.mesh.validate().ok) << r.mesh.validate().firstProblem;
  EXPECT_NEAR(r.mesh.area(), 4.0, 1e-12);
  EXPECT_EQ(edgesThroughSlit(r.mesh, {1, 0}, {0, 0}, 7, 8), 0);
  // The lips share the tip only; the attachment point (1, 0) is two vertices.
  const auto shared = sharedLipPoints(r.mesh, 7, 8);
  ASSERT_EQ(shared.size(), 1u);
  EXPECT_EQ(*shared.begin(), Vec2(0, 0));
  EXPECT_GE(lipVertices(r.mesh, 7).size(), 5u);
  EXPECT_GE(lipVertices(r.mesh, 8).size(), 5u);
  std::set<int> tags;
  for (const auto& e : r.mesh.boundaryEdges) tags.insert(e.ref);
  EXPECT_EQ(tags, (std::set<int>{1, 2, 3, 4, 7, 8}));
  // The cut is no boundary: 4 sides + 2 lips, each of length 1 or 2: perimeter 10.
  double perimeter = 0;
  for (const auto& e : r.mesh.boundaryEdges)
    perimeter += (r.mesh.vertices[std::size_t(e.a)] - r.mesh.vertices[std::size_t(e.b)]).norm();
  EXPECT_NEAR(perimeter, 10.0, 1e-12);
}

TEST(MeshSlitDomain, FreeSlitHasTwoTipsAndTwoLips) {
  const Domain d = Domain::rectangle(0, 0, 2, 1).withSlit({{0.5, 0.5}, {1.0, 0.5}, {1.5, 0.5}}, 5, 6);
  EXPECT_EQ(d.loops().size(), 2u);
  const ConstantMetricField metric(Metric2::isotropic(0.1));
  const MeshResult r = meshDomain(d, metric);
  EXPECT_TRUE(r.mesh.validate().ok) << r.mesh.validate().firstProblem;
  EXPECT_NEAR(r.mesh.area(), 2.0, 1e-12);
  EXPECT_EQ(edgesThroughSlit(r.mesh, {0.5, 0.5}, {1.5, 0.5}, 5, 6), 0);
  const auto shared = sharedLipPoints(r.mesh, 5, 6);
  EXPECT_EQ(shared.size(), 2u);  // the two tips
  EXPECT_TRUE(shared.count(Vec2(0.5, 0.5)) && shared.count(Vec2(1.5, 0.5)));
  // Deterministic: the same mesh twice.
  const MeshResult again = meshDomain(d, metric);
  EXPECT_EQ(again.mesh.vertices, r.mesh.vertices);
  EXPECT_EQ(again.mesh.triangles, r.mesh.triangles);
}

TEST(MeshSlitDomain, TipPointingOutOfTheDomainIsRefused) {
  // A loop with an outward spike: a zero-width gap outside the domain.
  BoundaryLoop loop;
  loop.points = {{0, 0}, {1, 0}, {1, 0.5}, {2, 0.5}, {1, 0.5}, {1, 1}, {0, 1}};
  EXPECT_THROW(
      {
        const Domain d(loop);
        meshDomain(d, ConstantMetricField(Metric2::isotropic(0.2)));
      },
      InputError);
}

TEST(MeshSlitDomain, CutThatMeetsAnotherSlitJoinsItOnTheSideItArrivesAt) {
  // The cut ahead of the first tip (the origin, going left) meets the free slit x = −0.5 at its
  // middle point, which the slit's loop visits twice; both orders of the free slit's points.
  for (const double dir : {1.0, -1.0}) {
    const Domain d = Domain::rectangle(-1, -1, 1, 1)
                         .withSlit({{1, 0}, {0, 0}}, 7, 8)
                         .withSlit({{-0.5, 0.5 * dir}, {-0.5, -0.5 * dir}}, 9, 10);
    const MeshResult r = meshDomain(d, ConstantMetricField(Metric2::isotropic(0.2)));
    EXPECT_TRUE(r.mesh.validate().ok) << r.mesh.validate().firstProblem;
    EXPECT_NEAR(r.mesh.area(), 4.0, 1e-12);
    EXPECT_EQ(edgesThroughSlit(r.mesh, {-0.5, 0.5 * dir}, {-0.5, -0.5 * dir}, 9, 10), 0) << dir;
  }
}

TEST(MeshSlitDomain, PiecesMeshedSideBySideAreTheSameAsOneAfterTheOther) {
  // Two balanced pieces and a thread-safe metric: with two threads the pieces are meshed
  // concurrently, one thread each; with one, one after the other. Same bits either way, and
  // progress comes from the calling thread only.
  const Domain d = Domain::rectangle(-1, -1, 1, 1).withSlit({{1, 0}, {0, 0}}, 7, 8);
  const ConstantMetricField metric(Metric2::fromSizes(0.06, 0.03, 0.4));
  const int saved = omp_get_max_threads();
  const auto caller = std::this_thread::get_id();
  MeshOptions options;
  bool otherThread = false;
  long reports = 0;
  options.progress = [&](const Progress&) {
    otherThread = otherThread || std::this_thread::get_id() != caller;
    ++reports;
  };
  omp_set_num_threads(1);
  const MeshResult one = meshDomain(d, metric, options);
  omp_set_num_threads(2);
  const MeshResult two = meshDomain(d, metric, options);
  omp_set_num_threads(saved);
  EXPECT_TRUE(two.mesh.validate().ok) << two.mesh.validate().firstProblem;
  EXPECT_GT(two.mesh.numVertices(), 1000);
  EXPECT_EQ(two.mesh.vertices, one.mesh.vertices);
  EXPECT_EQ(two.mesh.triangles, one.mesh.triangles);
  EXPECT_EQ(two.mesh.boundaryEdges.size(), one.mesh.boundaryEdges.size());
  EXPECT_EQ(two.metric.size(), one.metric.size());
  EXPECT_GT(reports, 0);
  EXPECT_FALSE(otherThread);
}
