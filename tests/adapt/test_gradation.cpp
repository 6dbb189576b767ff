// Mirrors adapt/gradation.hpp: the size growth along every edge is bounded afterwards, an
// already-graded field is untouched, anisotropy survives, metrics only grow.
#include "ablmg/adapt/gradation.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>
#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
// Worst violation over edges/directions of M_j ≥ η M_i (1 means satisfied exactly).
double worstViolation(const Mesh2& mesh, const std::vector<Metric2>& m, double hgrad) {
  double worst = 0;
  for (const auto& e : mesh.edges()) {
    for (int dir = 0; dir < 2; ++dir) {
      const int i = dir ? e[1] : e[0], j = dir ? e[0] : e[1];
      const double g = 1 + m[i].length(mesh.vertices[j] - mesh.vertices[i]) * std::log(hgrad);
      worst = std::max(worst, maxGeneralisedEigenvalue((1 / (g * g)) * m[i], m[j]));
    }
  }
  return worst;
}
}  // namespace

TEST(Gradation, BoundsSizeGrowthAlongEdges) {
  const Mesh2 mesh = fem::unitSquareMesh(30, 0.15, 2);
  // A sharp anisotropic feature on a coarse background: sizes jump ×100 across one edge.
  std::vector<Metric2> m(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 p = mesh.vertices[v];
    m[v] = std::abs(p.x() - 0.5) < 0.02 ? Metric2::fromSizes(0.05, 0.001, M_PI / 2) : Metric2::isotropic(0.1);
  }
  const auto before = m;
  ASSERT_GT(worstViolation(mesh, m, 1.3), 10.0);
  GradationOptions o;
  o.hgrad = 1.3;
  const auto stats = limitGradation(mesh, m, o);
  EXPECT_TRUE(stats.converged);
  EXPECT_GT(stats.corrections, 0);
  EXPECT_LE(worstViolation(mesh, m, 1.3), 1 / (1 - o.tolerance) + 1e-9);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    // Only refines: the new unit ball lies inside the old one.
    EXPECT_LE(maxGeneralisedEigenvalue(before[v], m[v]), 1 + 1e-9) << v;
  }
  // Anisotropy survives next to the feature: a vertex at x ≈ 0.5 keeps h1/h2 ≈ 50.
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (std::abs(mesh.vertices[v].x() - 0.5) < 0.005) { EXPECT_GT(m[v].eigen().h1 / m[v].eigen().h2, 20.0); }
  }
}

TEST(Gradation, LeavesGradedFieldUnchanged) {
  const Mesh2 mesh = fem::unitSquareMesh(20, 0.1, 5);
  std::vector<Metric2> m(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2 p = mesh.vertices[v];
    m[v] = Metric2::fromSizes(0.2 + 0.05 * p.x(), 0.1 + 0.02 * p.y(), 0.3);  // gentle variation
  }
  const auto before = m;
  const auto stats = limitGradation(mesh, m, {1.5});
  EXPECT_EQ(stats.corrections, 0);
  EXPECT_EQ(stats.sweeps, 1);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    EXPECT_EQ(m[v].m11(), before[v].m11());
    EXPECT_EQ(m[v].m12(), before[v].m12());
    EXPECT_EQ(m[v].m22(), before[v].m22());
  }
}

TEST(Gradation, RejectsBadInput) {
  const Mesh2 mesh = fem::unitSquareMesh(2);
  std::vector<Metric2> m(mesh.numVertices());
  EXPECT_THROW(limitGradation(mesh, m, {1.0}), InputError);
  m.pop_back();
  EXPECT_THROW(limitGradation(mesh, m, {1.5}), InputError);
}
