#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/population.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// Unit hexagonal lattice (metric h) on a rhombic patch, plus the metrics.
void hexPatch(double h, int n, std::vector<Vec2>& x, std::vector<Metric2>& m, const Vec2& origin = Vec2::Zero()) {
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      x.push_back(origin + h * Vec2(a + 0.5 * b, std::sqrt(3.0) / 2 * b));
      m.push_back(Metric2::isotropic(h));
    }
}

/// A bubble system of free interior nodes at `x`, metrics from `field`.
BubbleSystem interiorSystem(const DomainGeometry& geo, const std::vector<Vec2>& x, const MetricField& field) {
  NodeSet nodes;
  nodes.positions = x;
  nodes.kinds.assign(x.size(), NodeKind::Interior);
  nodes.loops.assign(x.size(), -1);
  nodes.arc.assign(x.size(), -1.0);
  BubbleSystem sys(geo, nodes, std::vector<double>(x.size(), -1.0));
  sys.updateMetrics(field);
  return sys;
}

/// A 15 × 15 hexagonal patch of spacing 0.1 (hexPatch) inside the rectangle [−1, 3]², in the
/// isotropic metric of that size: the set-up of the vacancy and steering tests.
struct HexPatch {
  Domain d = Domain::rectangle(-1, -1, 3, 3);
  DomainGeometry geo{d};
  ConstantMetricField field{Metric2::isotropic(0.1)};
  std::vector<Vec2> x;
  std::vector<Metric2> m;
  HexPatch() { hexPatch(0.1, 15, x, m); }
};
}  // namespace

TEST(Population, OverlapRatioIsSixInsideALatticeAndTwoOnALine) {
  std::vector<Vec2> x;
  std::vector<Metric2> m;
  hexPatch(0.1, 9, x, m);
  const auto a = overlapRatios(x, m, buildAdjacency(x, m, 1.7));
  EXPECT_NEAR(a[4 * 9 + 4], 6.0, 1e-9);  // centre node
  EXPECT_NEAR(a[0 * 9 + 4], 4.0, 1e-9);  // edge of the patch: 4 touching neighbours

  std::vector<Vec2> line;
  std::vector<Metric2> ml;
  for (int k = 0; k < 7; ++k) {
    line.emplace_back(0.2 * k, 0.0);
    ml.push_back(Metric2::fromSizes(0.2, 0.05, 0.0));
  }
  const auto b = overlapRatios(line, ml, buildAdjacency(line, ml, 1.7));
  EXPECT_NEAR(b[3], 2.0, 1e-9);
  // overlap raises it: squeeze the line by 20 %
  for (auto& p : line) p *= 0.8;
  const auto c = overlapRatios(line, ml, buildAdjacency(line, ml, 1.7));
  EXPECT_GT(c[3], 2.5);
}

TEST(Population, FillsAVacancyAndRemovesAnInterstitial) {
  HexPatch patch;
  const DomainGeometry& geo = patch.geo;
  const ConstantMetricField& field = patch.field;
  std::vector<Vec2>& x = patch.x;
  std::vector<Metric2>& m = patch.m;
  // vacancy at lattice node (7,7): drop it; interstitial: a node inside the triangle (3,3),(4,3),(3,4)
  const Vec2 hole = x[7 * 15 + 7];
  x.erase(x.begin() + 7 * 15 + 7);
  m.pop_back();
  const Vec2 extra = (x[3 * 15 + 3] + x[4 * 15 + 3] + x[3 * 15 + 4]) / 3;
  x.push_back(extra);
  m.push_back(Metric2::isotropic(0.1));
  BubbleSystem sys = interiorSystem(geo, x, field);
  const int before = sys.size();
  PopulationOptions o;  // no steering
  const PopulationChange c =
      adjustPopulation(sys, buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7), geo, field, o);
  EXPECT_EQ(c.deleted, 1);
  EXPECT_GE(c.inserted, 1);
  bool filled = false, removed = true;
  for (const Vec2& p : sys.nodes().positions) {
    filled = filled || (p - hole).norm() < 0.03;
    removed = removed && (p - extra).norm() > 1e-12;
  }
  EXPECT_TRUE(filled);
  EXPECT_TRUE(removed);
  EXPECT_EQ(sys.size(), before - c.deleted + c.inserted);
}

// Steering: a vacancy whose six neighbours have closed in by 15 % leaves a hole
// whose best insertion point is 0.7 from the nearest rim node: too close for minGap = 0.85,
// as in the slightly open spots a graded packing leaves. Below the target count the relaxed
// steering thresholds fill it; once steerUp is cleared (placeNodes does that when the count
// stops growing) they do not.
TEST(Population, SteeringFillsASmallHoleOnlyBelowTheTarget) {
  HexPatch patch;
  const DomainGeometry& geo = patch.geo;
  const ConstantMetricField& field = patch.field;
  std::vector<Vec2>& x = patch.x;
  const Vec2 hole = x[7 * 15 + 7];
  x.erase(x.begin() + 7 * 15 + 7);
  for (auto& p : x)
    if ((p - hole).norm() < 0.11) p = hole + 0.85 * (p - hole);
  auto insertedNearHole = [&](const PopulationOptions& o) {
    BubbleSystem sys = interiorSystem(geo, x, field);
    const PopulationChange c =
        adjustPopulation(sys, buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7), geo, field, o);
    int near = 0;  // the rim of the patch has real gaps: count only insertions near the hole
    for (int i = c.firstNew; i < sys.size(); ++i) near += (sys.nodes().positions[i] - hole).norm() < 0.15;
    return near;
  };
  PopulationOptions plain;  // no steering
  EXPECT_EQ(insertedNearHole(plain), 0);
  PopulationOptions steer;
  steer.target = 2 * long(x.size());
  EXPECT_EQ(insertedNearHole(steer), 1);
  steer.steerUp = false;
  EXPECT_EQ(insertedNearHole(steer), 0);
}

// Past 1.5× the aim no hole is filled: in a metric no packing fits, eq. (9) finds holes
// everywhere, and its insertions had grown the count 4–9× past the target.
TEST(Population, NoInsertionFarAboveTheTarget) {
  HexPatch patch;
  const DomainGeometry& geo = patch.geo;
  const ConstantMetricField& field = patch.field;
  std::vector<Vec2>& x = patch.x;
  x.erase(x.begin() + 7 * 15 + 7);  // a vacancy: filled without a target (FillsAVacancy...)
  auto inserted = [&](long target) {
    BubbleSystem sys = interiorSystem(geo, x, field);
    PopulationOptions o;
    o.target = target;
    return adjustPopulation(sys, buildAdjacency(sys.nodes().positions, sys.metrics(), 1.7), geo, field, o).inserted;
  };
  const long n = long(x.size());
  EXPECT_GE(inserted(n), 1);            // at the target: the vacancy is a real hole
  EXPECT_GE(inserted(n * 10 / 14), 1);  // 1.4× above: still filled
  EXPECT_EQ(inserted(n / 2), 0);        // 2× above: none
}
