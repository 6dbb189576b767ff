// mesher/quality.hpp: edge metric lengths, deviation histogram (eq. 13, Table 1), element quality
// q and its bins (Table 2), Lee's α on surfaces, JSON/text reports — on hand-computed values.
#include "ablmg/mesher/quality.hpp"

#include "ablmg/cli/stats_json.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <numeric>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// The equilateral triangle with unit edges, counter-clockwise.
Mesh2 unitEquilateral() {
  Mesh2 m;
  m.vertices = {{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}};
  m.triangles = {{0, 1, 2}};
  m.boundaryEdges = {{0, 1}, {1, 2}, {2, 0}};
  return m;
}

template <std::size_t N>
double sum(const std::array<double, N>& a) {
  return std::accumulate(a.begin(), a.end(), 0.0);
}

}  // namespace

TEST(Quality, UnitEquilateralInIdentityMetric) {
  const Mesh2 m = unitEquilateral();
  const std::vector<Metric2> identity(3);
  for (double l : edgeMetricLengths(m, identity)) EXPECT_NEAR(l, 1.0, 1e-15);
  EXPECT_NEAR(elementQualities(m, identity)[0], 1.0, 1e-15);
  const MeshQuality q = meshQuality(m, identity);
  EXPECT_TRUE(q.valid) << q.firstProblem;
  EXPECT_EQ(q.vertices, 3);
  EXPECT_EQ(q.triangles, 1);
  EXPECT_EQ(q.edges, 3);
  EXPECT_DOUBLE_EQ(q.edgeLengths.deviation[0], 1.0);  // ε = 0
  EXPECT_DOUBLE_EQ(q.edgeLengths.inSqrt2, 1.0);
  EXPECT_DOUBLE_EQ(q.elements.bins[4], 1.0);
}

TEST(Quality, ScaledMetricDoublesLengthsButKeepsShape) {
  const Mesh2 m = unitEquilateral();
  const std::vector<Metric2> metrics(3, Metric2::fromTensor(4, 0, 4));  // h = 1/2
  const MeshQuality q = meshQuality(m, metrics);
  EXPECT_NEAR(q.edgeLengths.min, 2.0, 1e-15);
  EXPECT_NEAR(q.edgeLengths.max, 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(q.edgeLengths.inSqrt2, 0.0);
  EXPECT_DOUBLE_EQ(q.edgeLengths.within10, 0.0);
  EXPECT_DOUBLE_EQ(q.edgeLengths.deviation[5], 1.0);  // ε = 1 > 5e
  EXPECT_NEAR(q.elements.min, 1.0, 1e-15);            // q is scale-invariant
}

TEST(Quality, AffineImageOfEquilateralIsPerfectInItsMetric) {
  // x = R(θ) diag(h1, h2) y maps the unit equilateral triangle of the y-plane onto the
  // equilateral triangle with unit edges of M = R diag(1/h1², 1/h2²) Rᵀ.
  const double h1 = 0.5, h2 = 0.1, theta = 0.3;
  const Metric2 M = Metric2::fromSizes(h1, h2, theta);
  Mesh2 m = unitEquilateral();
  for (auto& v : m.vertices) {
    const Vec2 s(h1 * v.x(), h2 * v.y());
    v = Vec2(std::cos(theta) * s.x() - std::sin(theta) * s.y(), std::sin(theta) * s.x() + std::cos(theta) * s.y());
  }
  const std::vector<Metric2> metrics(3, M);
  EXPECT_NEAR(elementQualities(m, metrics)[0], 1.0, 1e-12);
  for (double l : edgeMetricLengths(m, metrics)) EXPECT_NEAR(l, 1.0, 1e-12);
  // The same triangle is poor in the Euclidean metric.
  EXPECT_LT(elementQualities(m, std::vector<Metric2>(3))[0], 0.5);
}

TEST(Quality, RightIsoscelesTriangle) {
  // 4√3 · (1/2) / (1 + 1 + 2) = √3/2
  EXPECT_NEAR(triangleQuality({0, 0}, {1, 0}, {0, 1}, Metric2()), std::sqrt(3.0) / 2, 1e-15);
  // clockwise: negative, counted in the lowest bin
  EXPECT_NEAR(triangleQuality({0, 0}, {0, 1}, {1, 0}, Metric2()), -std::sqrt(3.0) / 2, 1e-15);
}

TEST(Quality, DeviationHistogramBinsOfTable1) {
  // ε = 0, .03 | .07 | .12 | .19 | .22 | .30, −  with e = 0.05
  const std::vector<double> l{1.0, 1.03, 1.07, 0.88, 1.19, 1.22, 1.3, 0.5};
  const EdgeLengthStats s = edgeLengthStats(l);
  const double n = double(l.size());
  EXPECT_EQ(s.count, 8);
  EXPECT_DOUBLE_EQ(s.deviation[0], 2 / n);
  EXPECT_DOUBLE_EQ(s.deviation[1], 1 / n);
  EXPECT_DOUBLE_EQ(s.deviation[2], 1 / n);
  EXPECT_DOUBLE_EQ(s.deviation[3], 1 / n);
  EXPECT_DOUBLE_EQ(s.deviation[4], 1 / n);
  EXPECT_DOUBLE_EQ(s.deviation[5], 2 / n);
  EXPECT_NEAR(sum(s.deviation), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.min, 0.5);
  EXPECT_DOUBLE_EQ(s.max, 1.3);
  EXPECT_NEAR(s.mean, (1.0 + 1.03 + 1.07 + 0.88 + 1.19 + 1.22 + 1.3 + 0.5) / n, 1e-15);
  EXPECT_DOUBLE_EQ(s.within10, 3 / n);  // 1, 1.03, 1.07 (0.88 is out)
  EXPECT_DOUBLE_EQ(s.inSqrt2, 7 / n);   // all but 0.5
  EXPECT_THROW(edgeLengthStats(l, 0.0), InputError);
}

TEST(Quality, ElementBinsOfTable2) {
  const std::vector<double> q{0.1, 0.3, 0.5, 0.7, 0.9, 1.0, -0.1, 0.6};
  const ElementQualityStats s = elementQualityStats(q);
  const double n = double(q.size());
  EXPECT_DOUBLE_EQ(s.bins[0], 2 / n);
  EXPECT_DOUBLE_EQ(s.bins[1], 1 / n);
  EXPECT_DOUBLE_EQ(s.bins[2], 1 / n);
  EXPECT_DOUBLE_EQ(s.bins[3], 2 / n);  // 0.6 opens [0.6, 0.8)
  EXPECT_DOUBLE_EQ(s.bins[4], 2 / n);
  EXPECT_NEAR(sum(s.bins), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.min, -0.1);
  EXPECT_DOUBLE_EQ(s.max, 1.0);
  const ElementQualityStats empty = elementQualityStats({});
  EXPECT_EQ(empty.count, 0);
  EXPECT_EQ(sum(empty.bins), 0.0);
}

TEST(Quality, SquareWithCentreVertexAndInvalidMesh) {
  Mesh2 m;
  m.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  m.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  m.boundaryEdges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const std::vector<Metric2> identity(5);
  MeshQuality q = meshQuality(m, identity);
  EXPECT_TRUE(q.valid) << q.firstProblem;
  EXPECT_EQ(q.edges, 8);
  EXPECT_NEAR(q.elements.min, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(q.elements.max, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(q.edgeLengths.mean, (4 + 4 * std::sqrt(0.5)) / 8, 1e-15);
  std::swap(m.triangles[0][0], m.triangles[0][1]);  // one clockwise triangle
  q = meshQuality(m, identity);
  EXPECT_FALSE(q.valid);
  EXPECT_FALSE(q.firstProblem.empty());
  EXPECT_LT(q.elements.min, 0);
  EXPECT_THROW(meshQuality(m, std::vector<Metric2>(4)), InputError);
}

TEST(Quality, SurfaceUsesLeeAlpha) {
  SurfaceMesh s;  // unit equilateral triangle in a tilted plane
  const Vec3 u = Vec3(1, 1, 1).normalized(), w = Vec3(1, -1, 0).normalized();
  s.vertices = {Vec3(0, 0, 2), Vec3(0, 0, 2) + u, Vec3(0, 0, 2) + 0.5 * u + std::sqrt(3.0) / 2 * w};
  s.triangles = {{0, 1, 2}};
  MeshQuality q = surfaceQuality(s, isotropicMetric3(1.0));
  EXPECT_EQ(q.dimension, 3);
  EXPECT_TRUE(q.valid);
  EXPECT_EQ(q.edges, 3);
  EXPECT_NEAR(q.elements.min, 1.0, 1e-12);
  EXPECT_NEAR(q.edgeLengths.mean, 1.0, 1e-12);
  q = surfaceQuality(s, isotropicMetric3(0.5));
  EXPECT_NEAR(q.edgeLengths.mean, 2.0, 1e-12);
  EXPECT_NEAR(q.elements.min, 1.0, 1e-12);
}

TEST(Quality, JsonAndTextReports) {
  const Mesh2 m = unitEquilateral();
  const MeshQuality q = meshQuality(m, std::vector<Metric2>(3));
  const nlohmann::json j = cli::qualityJson(q);
  EXPECT_EQ(j["triangles"], 1);
  EXPECT_EQ(j["valid"], true);
  EXPECT_EQ(j["edge_length"]["deviation"]["bins"].size(), 6u);
  EXPECT_EQ(j["element_quality"]["bins"].size(), 5u);
  EXPECT_DOUBLE_EQ(j["element_quality"]["min"].get<double>(), q.elements.min);
  const std::string text = toText(q);
  EXPECT_NE(text.find("3 edges; valid: yes"), std::string::npos) << text;
  EXPECT_NE(text.find("0.8-1.0 100.0%"), std::string::npos) << text;
}

TEST(Quality, LeeAlphaInThePlaneTakesTheWorstVertexMetric) {
  const Mesh2 m = unitEquilateral();
  // A metric field that is a scalar multiple of one tensor at every vertex: α = q (both are
  // scale-invariant), here 1 for the identity's multiples.
  const std::vector<Metric2> scaled = {Metric2::isotropic(1.0), Metric2::isotropic(0.5), Metric2::isotropic(3.0)};
  EXPECT_NEAR(leeAlphas(m, scaled)[0], 1.0, 1e-14);
  EXPECT_NEAR(elementQualities(m, scaled)[0], 1.0, 1e-14);
  // One vertex with a stretched metric: α is that vertex's q (eq. 19's minimum), below the
  // averaged-metric q.
  const Metric2 stretched = Metric2::fromSizes(1.0, 0.25, 0.0);
  const std::vector<Metric2> mixed = {Metric2::isotropic(1.0), Metric2::isotropic(1.0), stretched};
  const double expected = triangleQuality(m.vertices[0], m.vertices[1], m.vertices[2], stretched);
  EXPECT_LT(expected, 0.9);
  EXPECT_NEAR(leeAlphas(m, mixed)[0], expected, 1e-15);
  EXPECT_LT(leeAlphas(m, mixed)[0], elementQualities(m, mixed)[0]);
  const MeshQuality q = meshQuality(m, mixed);
  EXPECT_NEAR(q.leeAlpha.min, expected, 1e-15);
  EXPECT_EQ(cli::qualityJson(q)["lee_alpha"]["min"].get<double>(), q.leeAlpha.min);
  EXPECT_NE(toText(q).find("alpha (Lee"), std::string::npos);
  EXPECT_THROW(leeAlphas(m, std::vector<Metric2>(2)), InputError);
}

TEST(Quality, MetricJumpShareCountsSidesWhoseEndsDisagree) {
  const Mesh2 m = unitEquilateral();
  EXPECT_EQ(metricJumpShare(m, std::vector<Metric2>(3)), 0.0);
  // Vertex 2 asks for sizes a quarter of the others': its two sides are 4× longer measured there.
  const std::vector<Metric2> jump = {Metric2::isotropic(1.0), Metric2::isotropic(1.0), Metric2::isotropic(0.25)};
  EXPECT_NEAR(metricJumpShare(m, jump), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(metricJumpShare(m, jump, 3.9), 2.0 / 3.0, 1e-15);
  EXPECT_EQ(metricJumpShare(m, jump, 4.1), 0.0);
  // A stretched metric at vertex 2 whose long axis runs along side 2–0 (60°): side 1–2 is
  // 3.5× longer there (sqrt(0.25 + 0.75 · 16)), side 2–0 is not.
  const std::vector<Metric2> turned = {Metric2::isotropic(1.0), Metric2::isotropic(1.0),
                                       Metric2::fromSizes(1.0, 0.25, std::numbers::pi / 3)};
  EXPECT_NEAR(metricJumpShare(m, turned), 1.0 / 3.0, 1e-15);
  EXPECT_THROW(metricJumpShare(m, std::vector<Metric2>(2)), InputError);
}
