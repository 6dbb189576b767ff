#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/bubble_system.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

TEST(BubbleSystem, SegmentNodesPushedIntoACornerStayDistinctAndInOrder) {
  // Three Segment nodes packed within 1e-9 of the corner (0, 0) of a unit square, under a
  // metric a million times coarser: the repulsion drives them towards both corners with
  // steps far longer than their gaps. Each chain keeps its order and no two nodes (nor a
  // node and a corner) ever share a point.
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const DomainGeometry geo(d);
  ConstantMetricField field(Metric2::isotropic(0.5));
  NodeSet n;
  std::vector<double> arc;
  auto add = [&](NodeKind kind, double s) {
    n.positions.push_back(geo.pointAt(0, s));
    n.kinds.push_back(kind);
    n.loops.push_back(0);
    n.arc.push_back(geo.indexArc(0, s));
    arc.push_back(s);
  };
  for (int k = 0; k < 4; ++k) add(NodeKind::Vertex, geo.loops()[0].cum[k]);
  for (double s : {1e-9, 2e-9, 3e-9, 4.0 - 1e-9, 4.0 - 3e-9}) add(NodeKind::Segment, s);
  BubbleSystem sys(geo, n, arc);
  sys.updateMetrics(field);
  DynamicsParams p;
  for (int step = 0; step < 100; ++step) {
    const AdjacencyLists adj = buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7);
    sys.computeForces(adj, p);
    sys.advance(p);
    std::vector<double> bottom, left;  // arcs of the chains on y = 0 and on x = 0
    for (int i = 4; i < sys.size(); ++i) {
      for (int j = 0; j < i; ++j) ASSERT_NE(sys.nodes().positions[i], sys.nodes().positions[j]) << step;
      (i < 7 ? bottom : left).push_back(sys.arcLength(i));
    }
    ASSERT_TRUE(std::is_sorted(bottom.begin(), bottom.end())) << step;
    ASSERT_GT(bottom.front(), 0.0);
    ASSERT_LT(bottom.back(), 1.0);
    ASSERT_GT(left.front(), 3.0);  // 4 − 1e-9 lies above 4 − 3e-9
    ASSERT_GT(left[0], left[1]) << step;
  }
  // The repulsion spreads them out along their edges.
  EXPECT_GT(sys.arcLength(6) - sys.arcLength(4), 0.1);
}

TEST(NodeSet, CoincidentNodesDropInteriorBeforeBoundaryAndHigherIndexFirst) {
  NodeSet n;
  n.positions = {{0, 0}, {0.5, 0}, {0.5, 0}, {0.2, 0.3}, {0.2, 0.3}, {0.2, 0.3}, {0.7, 0.7}};
  n.kinds = {NodeKind::Vertex,   NodeKind::Interior, NodeKind::Segment, NodeKind::Interior,
             NodeKind::Interior, NodeKind::Interior, NodeKind::Interior};
  n.loops = {0, -1, 0, -1, -1, -1, -1};
  n.arc = {0, -1, 0.5, -1, -1, -1, -1};
  std::vector<Metric2> m(n.positions.size(), Metric2::isotropic(1.0));
  const AdjacencyLists adj = buildAdjacency(n.positions, m, 1.7);
  std::vector<char> drop;
  EXPECT_EQ(coincidentNodes(n, adj, drop), 3);
  EXPECT_EQ(drop, (std::vector<char>{0, 1, 0, 0, 1, 1, 0}));  // the Segment node and node 3 stay
}
