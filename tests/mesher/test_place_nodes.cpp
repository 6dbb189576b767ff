#include "ablmg/core/error.hpp"
#include "ablmg/mesher/place_nodes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// Nearest-neighbour metric distance (averaged tensor, eq. 3) of every interior node.
std::vector<double> nearestInterior(const PlacementResult& r) {
  std::vector<double> out;
  for (int i = 0; i < r.nodes.size(); ++i) {
    if (r.nodes.kinds[i] != NodeKind::Interior) continue;
    double best = 1e300;
    for (int j : r.adjacency.neighbours(i)) {
      const Vec2 d = r.nodes.positions[j] - r.nodes.positions[i];
      best = std::min(best, std::sqrt(0.5 * (r.metrics[i].squaredLength(d) + r.metrics[j].squaredLength(d))));
    }
    out.push_back(best);
  }
  return out;
}

double fractionIn(const std::vector<double>& v, double lo, double hi) {
  return double(std::count_if(v.begin(), v.end(), [&](double x) { return x >= lo && x <= hi; })) / double(v.size());
}

Domain randomDomain(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.7, 1.3);
  BoundaryLoop outer;
  const int n = 7 + int(seed % 5);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    const double r = (k % 2 ? 0.55 : 1.0) * u(rng);  // alternating radii: concave
    outer.points.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  std::vector<BoundaryLoop> holes;
  if (seed % 2) {
    BoundaryLoop h;
    for (int k = 0; k < 5; ++k) {
      const double t = 2 * std::numbers::pi * k / 5;
      h.points.emplace_back(0.05 + 0.2 * std::cos(t), -0.03 + 0.2 * std::sin(t));
    }
    holes.push_back(h);
  }
  return Domain(outer, holes);
}

std::unique_ptr<MetricField> randomMetric(std::uint64_t seed) {
  std::mt19937_64 rng(seed * 7919 + 1);
  std::uniform_real_distribution<double> u(0, 1);
  const double h = 0.05 + 0.04 * u(rng), a = 0.3 + 0.5 * u(rng), k = 1 + 3 * u(rng), r = 0.3 + 0.7 * u(rng);
  const std::string h1 = std::to_string(h) + "*(1+" + std::to_string(a) + "*sin(" + std::to_string(k) + "*x+y))";
  return std::make_unique<AnalyticMetricField>(AnalyticMetricField::Form::Sizes, h1, std::to_string(r) + "*" + h1,
                                               std::to_string(2 * u(rng)) + "*x");
}

bool onBoundary(const Domain& d, const Vec2& p) { return d.distanceToBoundary(p) < 1e-9; }

}  // namespace

TEST(PlaceNodes, ConstantIsotropicSquareIsHexagonal) {
  const Domain d = Domain::rectangle(0, 0, 2, 2);
  ConstantMetricField m(Metric2::isotropic(0.05));
  const PlacementResult r = placeNodes(d, m);
  EXPECT_TRUE(r.adjacency.isSymmetric());
  EXPECT_FALSE(r.stats.hitStepCap);
  int far = 0, hex = 0;
  for (int i = 0; i < r.nodes.size(); ++i) {
    if (d.distanceToBoundary(r.nodes.positions[i]) < 0.2) continue;  // 4 layers off the boundary
    ++far;
    int six = 0;
    double lo = 1e9, hi = 0;
    for (int j : r.adjacency.neighbours(i)) {
      const double l = (r.nodes.positions[j] - r.nodes.positions[i]).norm() / 0.05;
      if (l < 1.3) {
        ++six;
        lo = std::min(lo, l);
        hi = std::max(hi, l);
      }
    }
    hex += six == 6 && lo > 0.95 && hi < 1.05;
  }
  ASSERT_GT(far, 600);
  EXPECT_GT(double(hex) / far, 0.95);
  EXPECT_NEAR(double(r.stats.finalNodes) / r.stats.predictedNodes, 1.0, 0.05);
}

TEST(PlaceNodes, ConstantAnisotropicIsTheAffineImageOfIsotropic) {
  // Square [0,1.5]² at h = 0.05 vs its image under A = M^{-1/2}/0.05 with M = (0.12, 0.03, 0.6):
  // A maps iso-unit vectors to M-unit vectors, so the packings must have the same statistics.
  const Metric2 ma = Metric2::fromSizes(0.12, 0.03, 0.6);
  const MetricEigen e = ma.eigen();
  Eigen::Matrix2d rot;
  rot << std::cos(e.theta), -std::sin(e.theta), std::sin(e.theta), std::cos(e.theta);
  const Eigen::Matrix2d A = rot * Eigen::Vector2d(e.h1, e.h2).asDiagonal() * rot.transpose() / 0.05;
  BoundaryLoop sq, img;
  sq.points = {{0, 0}, {1.5, 0}, {1.5, 1.5}, {0, 1.5}};
  for (const auto& p : sq.points) img.points.push_back(A * p);
  const PlacementResult ri = placeNodes(Domain(sq), ConstantMetricField(Metric2::isotropic(0.05)));
  const PlacementResult ra = placeNodes(Domain(img), ConstantMetricField(ma));
  // Not bit-identical: the lattice's phase relative to the walls differs (seed probe grid),
  // which moves boundary-layer defects; the statistics agree.
  EXPECT_NEAR(double(ra.nodes.size()) / ri.nodes.size(), 1.0, 0.03);
  const auto ni = nearestInterior(ri), na = nearestInterior(ra);
  EXPECT_NEAR(fractionIn(na, 0.85, 1.15), fractionIn(ni, 0.85, 1.15), 0.02);
  EXPECT_GT(fractionIn(na, 0.85, 1.15), 0.95);
  EXPECT_GT(fractionIn(ni, 0.85, 1.15), 0.95);
  double si = 0, sa = 0;
  for (double x : ni) si += x;
  for (double x : na) sa += x;
  EXPECT_NEAR(sa / na.size(), si / ni.size(), 0.025);
}

TEST(PlaceNodes, RandomDomainsAndMetricsKeepEveryBubbleInside) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Domain d = randomDomain(seed);
    const auto m = randomMetric(seed);
    PlacementOptions o;
    o.maxSteps = 300;
    const PlacementResult r = placeNodes(d, *m, o);
    ASSERT_GT(r.nodes.size(), 100) << seed;
    EXPECT_TRUE(r.adjacency.isSymmetric()) << seed;
    ASSERT_EQ(int(r.metrics.size()), r.nodes.size());
    // vertex bubbles are exactly the PSLG corners, unmoved
    std::vector<Vec2> corners;
    for (const auto& loop : d.loops())
      for (const auto& p : loop.points) corners.push_back(p);
    int vertices = 0;
    for (int i = 0; i < r.nodes.size(); ++i) {
      const Vec2& p = r.nodes.positions[i];
      switch (r.nodes.kinds[i]) {
        case NodeKind::Vertex:
          ++vertices;
          EXPECT_TRUE(std::find(corners.begin(), corners.end(), p) != corners.end()) << seed << " " << i;
          break;
        case NodeKind::Segment:
          EXPECT_TRUE(onBoundary(d, p)) << seed << " " << i;
          break;
        case NodeKind::Interior:
          EXPECT_TRUE(d.contains(p) && !onBoundary(d, p)) << seed << " node " << i << " at " << p.transpose();
          break;
      }
    }
    EXPECT_EQ(vertices, int(corners.size()));
    // boundary edges: each loop closed, domain on the left (signed area of outer > 0, holes < 0)
    std::vector<double> signedArea(d.loops().size(), 0.0);
    std::vector<int> count(d.loops().size(), 0);
    for (const auto& be : r.boundaryEdges) {
      const int l = r.nodes.loops[be.a];
      ASSERT_EQ(l, r.nodes.loops[be.b]);
      signedArea[l] += 0.5 * cross(r.nodes.positions[be.a], r.nodes.positions[be.b]);
      ++count[l];
      EXPECT_EQ(be.ref, 1);
    }
    EXPECT_GT(signedArea[0], 0.9 * d.area()) << seed;
    for (std::size_t l = 1; l < signedArea.size(); ++l) EXPECT_LT(signedArea[l], 0) << seed;
  }
}

TEST(PlaceNodes, BoundaryEdgesCarryTheSegmentTags) {
  const Domain d = Domain::rectangle(0, 0, 1, 0.5);
  const PlacementResult r = placeNodes(d, ConstantMetricField(Metric2::isotropic(0.1)));
  ASSERT_EQ(r.boundaryEdges.size(), 10u + 5u + 10u + 5u);
  for (const auto& e : r.boundaryEdges) {
    const Vec2 mid = 0.5 * (r.nodes.positions[e.a] + r.nodes.positions[e.b]);
    const int expect = mid.y() == 0 ? 1 : mid.x() == 1 ? 2 : mid.y() == 0.5 ? 3 : 4;
    EXPECT_EQ(e.ref, expect) << mid.transpose();
    EXPECT_NEAR((r.nodes.positions[e.b] - r.nodes.positions[e.a]).norm(), 0.1, 1e-6);
  }
}

TEST(PlaceNodes, DeterministicAcrossRunsAndThreadCounts) {
  const Domain d = randomDomain(3);
  const auto m = randomMetric(3);
  PlacementOptions o;
  o.maxSteps = 200;
  o.threads = 1;
  const PlacementResult a = placeNodes(d, *m, o);
  const PlacementResult b = placeNodes(d, *m, o);
  o.threads = 2;
  const PlacementResult c = placeNodes(d, *m, o);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.nodes.size(), c.nodes.size());
  for (int i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes.positions[i], b.nodes.positions[i]) << i;
    ASSERT_EQ(a.nodes.positions[i], c.nodes.positions[i]) << i;
  }
  EXPECT_EQ(a.adjacency.ids, c.adjacency.ids);
}

TEST(PlaceNodes, SeedGivesAnotherPackingOfTheSameQuality) {
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const ConstantMetricField m(Metric2::isotropic(0.05));
  PlacementOptions o;
  const PlacementResult r0 = placeNodes(d, m, o);
  o.seed = 7;
  const PlacementResult a = placeNodes(d, m, o);
  o.threads = 2;
  const PlacementResult b = placeNodes(d, m, o);  // same seed, other thread count: same nodes
  o.threads = 0;
  o.seed = 8;
  const PlacementResult c = placeNodes(d, m, o);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.nodes.positions, b.nodes.positions);
  // Different packings: most interior nodes are elsewhere.
  const auto differ = [](const PlacementResult& x, const PlacementResult& y) {
    if (x.nodes.size() != y.nodes.size()) return true;
    int moved = 0;
    for (int i = 0; i < x.nodes.size(); ++i) moved += x.nodes.positions[i] != y.nodes.positions[i];
    return moved > x.nodes.size() / 2;
  };
  EXPECT_TRUE(differ(r0, a));
  EXPECT_TRUE(differ(a, c));
  // The same statistics within noise: node count within 1 %, packing figure within 2 points.
  for (const PlacementResult* r : {&a, &c}) {
    EXPECT_NEAR(double(r->nodes.size()), double(r0.nodes.size()), 0.01 * r0.nodes.size());
    EXPECT_NEAR(r->stats.nearestInRange, r0.stats.nearestInRange, 0.02);
    EXPECT_GT(r->stats.nearestInRange, 0.9);
  }
}

TEST(PlaceNodes, RefusesTooManyNodesBeforeAllocating) {
  PlacementOptions o;
  o.maxNodes = 1000;
  EXPECT_THROW(placeNodes(Domain::rectangle(0, 0, 1, 1), ConstantMetricField(Metric2::isotropic(0.001)), o),
               InputError);
}

// The paper's §4.3 disk of radius 10 with its three metrics: ±5 % of N*, 95 % nearest neighbours in [0.85, 1.15], ×100 residual drop.
struct DiskCase {
  const char* h1;
  const char* h2;
  const char* theta;
};
class PaperDisk : public ::testing::TestWithParam<DiskCase> {};

TEST_P(PaperDisk, CountQualityAndConvergence) {
  const DiskCase c = GetParam();
  AnalyticMetricField m(AnalyticMetricField::Form::Sizes, c.h1, c.h2, c.theta);
  const PlacementResult r = placeNodes(Domain::disk({0, 0}, 10), m);
  const auto& s = r.stats;
  EXPECT_NEAR(double(s.finalNodes) / s.predictedNodes, 1.0, 0.05);
  EXPECT_GE(fractionIn(nearestInterior(r), 0.85, 1.15), 0.95);
  EXPECT_DOUBLE_EQ(nearestNeighbourShare(r),
                   fractionIn(nearestInterior(r), 0.85, 1.15));  // what `ablmg mesh --report` says
  EXPECT_LE(s.finalResidual, 0.01 * s.initialResidual);
  EXPECT_FALSE(s.hitStepCap);
  EXPECT_TRUE(r.adjacency.isSymmetric());
}

INSTANTIATE_TEST_SUITE_P(Section43, PaperDisk,
                         ::testing::Values(DiskCase{"0.5", "0.2", "pi/4"},
                                           DiskCase{"0.15*abs(sqrt(x^2+y^2)-6)+0.2",
                                                    "0.5*(0.15*abs(sqrt(x^2+y^2)-6)+0.2)", "0"},
                                           DiskCase{"0.1*abs(y)+0.2", "0.5*(0.1*abs(y)+0.2)", "0"}));

TEST(PlaceNodes, WarmStartFromConvergedNodesNeedsFewSteps) {
  // Seeds = the interior nodes of a converged packing for the same metric: nearly all of them
  // are taken, so the dynamics has less to do (its target refers to a fresh lattice's residual,
  // not to its own small one, which it could stall above: measured 69 steps against 229 cold).
  // Defect annealing is off on both sides: its passes add the same ~100 steps to each run
  // (defects.hpp), which says nothing about the warm start.
  AnalyticMetricField m(AnalyticMetricField::Form::Sizes, "0.1*abs(y)+0.2", "0.5*(0.1*abs(y)+0.2)", "0");
  const Domain disk = Domain::disk({0, 0}, 10);
  PlacementOptions noAnnealing;
  noAnnealing.defectPasses = 0;
  const PlacementResult cold = placeNodes(disk, m, noAnnealing);
  PlacementOptions o = noAnnealing;
  for (int i = 0; i < cold.nodes.size(); ++i)
    if (cold.nodes.kinds[i] == NodeKind::Interior) o.warmStart.push_back(cold.nodes.positions[i]);
  const PlacementResult warm = placeNodes(disk, m, o);
  EXPECT_NEAR(double(warm.stats.initialNodes), double(cold.stats.finalNodes), 0.01 * cold.stats.finalNodes);
  EXPECT_LT(warm.stats.steps, 0.7 * cold.stats.steps)
      << "warm residual " << warm.stats.initialResidual << " -> " << warm.stats.finalResidual << ", cold "
      << cold.stats.initialResidual << " -> " << cold.stats.finalResidual;
  EXPECT_GE(fractionIn(nearestInterior(warm), 0.85, 1.15), 0.95);
}

TEST(PlaceNodes, QualityPlateauStopsEarlierWithTheSamePacking) {
  // The ring metric at 0.6 of the paper's size (≈ 12k nodes) converges slowly: measured 181
  // steps to ×100, 140 with a 20-step plateau rule, the same packing (87.1 % of nearest
  // neighbours within ±10 %). (With eq. (8)'s harmonic pair distance, before pairDistance in
  // bubble_force.hpp: 326 steps, 250 with a 50-step plateau.)
  const std::string h1 = "0.6*(0.15*abs(sqrt(x^2+y^2)-6)+0.2)";
  AnalyticMetricField m(AnalyticMetricField::Form::Sizes, h1, "0.5*" + h1, "0");
  const Domain disk = Domain::disk({0, 0}, 10);
  // Both without the defect annealing (defects.hpp), which runs only after convergence and
  // would credit the full run with its gain (89.7 % vs 86.7 %).
  PlacementOptions o;
  o.defectPasses = 0;
  const PlacementResult full = placeNodes(disk, m, o);
  o.plateauSteps = 20;
  const PlacementResult early = placeNodes(disk, m, o);
  EXPECT_FALSE(full.stats.qualityPlateau);
  EXPECT_TRUE(early.stats.qualityPlateau);
  EXPECT_LT(early.stats.steps, full.stats.steps);
  EXPECT_NEAR(fractionIn(nearestInterior(early), 0.9, 1.1), fractionIn(nearestInterior(full), 0.9, 1.1), 0.01);
}
