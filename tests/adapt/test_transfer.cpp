// Mirrors adapt/transfer.hpp: interpolation is exact on linear fields between unrelated meshes
// of one polygon; the L2 projection keeps ∫u to round-off and reproduces linear fields; the
// supermesh pieces tile the domain; the limiter keeps the bounds and the mass; the result
// does not depend on the thread count; bad input is an InputError naming the field.
#include "ablmg/adapt/transfer.hpp"

#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>

#include "square_with_hole.hpp"
#include <omp.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {

using test::squareWithHole;

/// Two unrelated meshes of squareWithHole(): a perturbed structured one and a bubble mesh.
struct MeshPair {
  Mesh2 a, b;
};
const MeshPair& meshes() {
  static const MeshPair pair{fem::structuredMesh(squareWithHole(), 24, 24, 0.15, 3),
                             uniformMesh(squareWithHole(), 700).mesh};
  return pair;
}

Eigen::VectorXd sample(const Mesh2& mesh, double (*u)(const Vec2&)) {
  Eigen::VectorXd v(mesh.numVertices());
  for (int i = 0; i < mesh.numVertices(); ++i) v[i] = u(mesh.vertices[std::size_t(i)]);
  return v;
}
double linearU(const Vec2& p) { return 1.5 - 2 * p.x() + 0.75 * p.y(); }
double peakU(const Vec2& p) { return std::exp(-8 * ((p - Vec2(2.8, 3.1)).squaredNorm())); }
double layerU(const Vec2& p) { return std::tanh((p.x() + 0.5 * p.y() - 2.3) / 0.05); }

}  // namespace

TEST(Transfer, ClipOfTwoTrianglesHasTheRightAreaAndEdgeContactIsEmpty) {
  const std::array<Vec2, 3> a{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, b{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)};
  const auto p = clipTriangles(a, b);  // the triangle (0,0), (1,0), (1/2,1/2): area 1/4
  double area = 0;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) area += 0.5 * cross(p[i] - p[0], p[i + 1] - p[0]);
  EXPECT_NEAR(area, 0.25, 1e-15);
  const std::array<Vec2, 3> below{Vec2(0, 0), Vec2(1, -1), Vec2(1, 0)};  // shares the edge (0,0)-(1,0) with a
  EXPECT_TRUE(clipTriangles(a, below).empty());
  EXPECT_TRUE(clipTriangles(a, {Vec2(2, 2), Vec2(3, 2), Vec2(2, 3)}).empty());
}

TEST(Transfer, SupermeshPiecesTileTheDomain) {
  const auto& [a, b] = meshes();
  double area = 0;
  long pieces = 0;
  forEachSupermeshPiece(a, b, [&](int o, int n, std::span<const Vec2> poly) {
    ASSERT_GE(poly.size(), 3u);
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) area += 0.5 * cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    ++pieces;
  });
  EXPECT_NEAR(area, squareWithHole().area(), 1e-12 * squareWithHole().area());
  EXPECT_GT(pieces, a.numTriangles());
  EXPECT_LT(pieces, 10L * (a.numTriangles() + b.numTriangles()));  // linear, not quadratic
}

TEST(Transfer, InterpolationIsExactOnLinearFieldsBothWays) {
  const auto& [a, b] = meshes();
  for (int dir = 0; dir < 2; ++dir) {
    const Mesh2& from = dir ? b : a;
    const Mesh2& to = dir ? a : b;
    const std::vector<Eigen::VectorXd> in{sample(from, linearU), sample(from, peakU)};
    TransferStats stats;
    const auto out = transferFields(from, to, in, {TransferMethod::Interpolation}, &stats);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_LT((out[0] - sample(to, linearU)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(stats.outsideVertices, 0);
  }
}

TEST(Transfer, ProjectionConservesMassAndReproducesLinearFields) {
  const auto& [a, b] = meshes();
  for (int dir = 0; dir < 2; ++dir) {
    const Mesh2& from = dir ? b : a;
    const Mesh2& to = dir ? a : b;
    const std::vector<Eigen::VectorXd> in{sample(from, linearU), sample(from, peakU), sample(from, layerU)};
    TransferStats stats;
    const auto out = transferFields(from, to, in, {}, &stats);
    EXPECT_LT((out[0] - sample(to, linearU)).cwiseAbs().maxCoeff(), 1e-12);
    for (int f = 0; f < 3; ++f) {
      const double before = integrate(from, in[std::size_t(f)]), after = integrate(to, out[std::size_t(f)]);
      EXPECT_NEAR(after, before, 1e-12 * std::abs(before)) << "field " << f;
      EXPECT_DOUBLE_EQ(stats.massOld[std::size_t(f)], before);
    }
    EXPECT_LT(stats.maxRelativeMassDefect(), 1e-12);
    EXPECT_NEAR(stats.supermeshArea, squareWithHole().area(), 1e-12 * squareWithHole().area());
    EXPECT_LT(stats.solverIterations, 60);
  }
}

TEST(Transfer, LimiterKeepsTheBoundsAndTheMass) {
  const auto& [a, b] = meshes();
  const std::vector<Eigen::VectorXd> in{sample(a, layerU)};
  const auto plain = transferFields(a, b, in, {});
  ASSERT_GT(plain[0].maxCoeff(), 1.0 + 1e-6);  // the steep layer makes the projection overshoot
  TransferStats stats;
  const auto limited = transferFields(a, b, in, {TransferMethod::L2Projection, true}, &stats);
  EXPECT_LE(limited[0].maxCoeff(), in[0].maxCoeff());
  EXPECT_GE(limited[0].minCoeff(), in[0].minCoeff());
  EXPECT_NEAR(integrate(b, limited[0]), integrate(a, in[0]), 1e-12 * integrate(a, in[0].cwiseAbs()));
}

TEST(Transfer, SameBitsOnOneAndTwoThreads) {
  const auto& [a, b] = meshes();
  const std::vector<Eigen::VectorXd> in{sample(a, peakU), sample(a, layerU)};
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = transferFields(a, b, in, {});
  const auto oneI = transferFields(a, b, in, {TransferMethod::Interpolation});
  omp_set_num_threads(2);
  const auto two = transferFields(a, b, in, {});
  const auto twoI = transferFields(a, b, in, {TransferMethod::Interpolation});
  omp_set_num_threads(3);  // the mass solve's blocks shared out unevenly
  const auto three = transferFields(a, b, in, {});
  omp_set_num_threads(saved);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(one[std::size_t(f)], two[std::size_t(f)]);
    EXPECT_EQ(one[std::size_t(f)], three[std::size_t(f)]);
    EXPECT_EQ(oneI[std::size_t(f)], twoI[std::size_t(f)]);
  }
}

TEST(Transfer, CurvedBoundaryVerticesOutsideTakeTheClosestBoundaryValue) {
  // Two polygonal discs: the new boundary nodes lie on the circle, outside the old chords.
  const Mesh2 from = uniformMesh(Domain::disk(Vec2(0, 0), 1.0, 40), 300).mesh;
  const Mesh2 to = uniformMesh(Domain::disk(Vec2(0, 0), 1.0, 57), 500).mesh;
  const std::vector<Eigen::VectorXd> in{sample(from, linearU)};
  TransferStats stats;
  const auto out = transferFields(from, to, in, {TransferMethod::Interpolation}, &stats);
  EXPECT_GT(stats.outsideVertices, 0);
  // chord sagitta of 40 samples: 1 − cos(π/40) ≈ 3.1e−3; |∇u| = 2.14
  EXPECT_LT((out[0] - sample(to, linearU)).cwiseAbs().maxCoeff(), 2.14 * 3.2e-3);
}

TEST(Transfer, BadFieldSizeIsAnInputErrorNamingTheField) {
  const auto& [a, b] = meshes();
  const std::vector<Eigen::VectorXd> in{sample(a, linearU), Eigen::VectorXd::Zero(5)};
  try {
    transferFields(a, b, in, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("field 1 has 5 values"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseTransferMethod("nearest"), InputError);
}
