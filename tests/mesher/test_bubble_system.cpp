#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/bubble_system.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace ablmg;
using namespace ablmg::mesher;

TEST(BubbleSystem, TwoBubblesRelaxToTheRestLength) {
  const Domain d = Domain::rectangle(-5, -5, 5, 5);
  const DomainGeometry geo(d);
  ConstantMetricField field(Metric2::fromSizes(1.0, 0.25, 0.0));
  NodeSet n;
  n.positions = {{0, 0}, {0.6, 0}};  // w = 0.6: repulsive
  n.kinds = {NodeKind::Interior, NodeKind::Interior};
  n.loops = {-1, -1};
  n.arc = {-1, -1};
  BubbleSystem sys(geo, n, {-1, -1});
  sys.updateMetrics(field);
  const AdjacencyLists adj = buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7);
  DynamicsParams p;
  double r0 = sys.computeForces(adj, p), r = r0;
  for (int s = 0; s < 300; ++s) {
    sys.advance(p);
    r = sys.computeForces(adj, p);
  }
  EXPECT_LT(r, 1e-3 * r0);
  EXPECT_NEAR((sys.nodes().positions[1] - sys.nodes().positions[0]).norm(), 1.0, 1e-3);  // h1 along x
  EXPECT_NEAR(sys.nodes().positions[0].y(), 0.0, 1e-12);
}

TEST(BubbleSystem, VertexFixedSegmentOnItsLoopInteriorInside) {
  // A crowded triangle: corners fixed, segment nodes stay on the polyline between their
  // corners, interior nodes never leave, whatever the forces.
  BoundaryLoop loop;
  loop.points = {{0, 0}, {1, 0}, {0, 1}};
  const Domain d(loop);
  const DomainGeometry geo(d);
  ConstantMetricField field(Metric2::isotropic(0.3));
  NodeSet n;
  std::vector<double> arc;
  for (int k = 0; k < 3; ++k) {
    n.positions.push_back(loop.points[k]);
    n.kinds.push_back(NodeKind::Vertex);
    n.loops.push_back(0);
    n.arc.push_back(k);
    arc.push_back(geo.loops()[0].cum[k]);
  }
  n.positions.push_back(geo.pointAt(0, 0.5));
  n.kinds.push_back(NodeKind::Segment);
  n.loops.push_back(0);
  n.arc.push_back(0.5);
  arc.push_back(0.5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.02, 0.45);
  for (int k = 0; k < 30; ++k) {
    n.positions.emplace_back(u(rng), u(rng));
    n.kinds.push_back(NodeKind::Interior);
    n.loops.push_back(-1);
    n.arc.push_back(-1);
    arc.push_back(-1);
  }
  BubbleSystem sys(geo, n, arc);
  sys.updateMetrics(field);
  DynamicsParams p;
  for (int s = 0; s < 200; ++s) {
    const AdjacencyLists adj = buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7);
    sys.computeForces(adj, p);
    sys.advance(p);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(sys.nodes().positions[k], loop.points[k]);
    const Vec2 q = sys.nodes().positions[3];
    ASSERT_EQ(q.y(), 0.0);
    ASSERT_GT(q.x(), 0.0);
    ASSERT_LT(q.x(), 1.0);
    for (int i = 4; i < sys.size(); ++i) ASSERT_TRUE(d.contains(sys.nodes().positions[i])) << s << " " << i;
  }
}
