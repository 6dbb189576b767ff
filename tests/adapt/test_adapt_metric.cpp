// The mesher-free steps of adapt/adaptive_loop.hpp: adaptMetric() (recover → metric →
// gradation at a target complexity) and metricQuality().
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/gradation.hpp"
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>
#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {
std::vector<double> waveFront(const Mesh2& mesh) {
  const Eigen::VectorXd u = fem::interpolate(mesh, fem::makeProblem("wavefront").u);
  return {u.data(), u.data() + u.size()};
}
}  // namespace

TEST(AdaptMetric, HitsTargetComplexityWithAndWithoutGradation) {
  const Mesh2 mesh = fem::unitSquareMesh(50, 0.15, 3);
  const auto u = waveFront(mesh);
  for (double hgrad : {0.0, 1.3}) {
    AdaptOptions o;
    o.hgrad = hgrad;
    const AdaptedMetric a = adaptMetric(mesh, u, 8000, o);
    const auto& m = a.metric;
    const GradationStats& gs = a.gradation;
    ASSERT_EQ(int(m.size()), mesh.numVertices());
    EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(8000), 1.0, 0.01) << "hgrad " << hgrad;
    EXPECT_GT(a.secondsRecover, 0);
    EXPECT_GT(a.secondsMetric, 0);
    if (hgrad <= 1) { EXPECT_EQ(gs.sweeps, 0); }
    if (hgrad > 1) {
      EXPECT_TRUE(gs.converged);
      EXPECT_GT(gs.corrections, 0);
    }
    // hmax = ∞ becomes a quarter of the diagonal √2.
    for (const auto& x : m) EXPECT_LE(x.eigen().h1, 0.25 * std::sqrt(2.0) * (1 + 1e-9));
    // Refined at the front (r = 0.7 around (−0.05, −0.05)), coarse away from it.
    double hFront = 1, hFar = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double r = (mesh.vertices[v] + Vec2(0.05, 0.05)).norm();
      if (std::abs(r - 0.7) < 0.01) hFront = std::min(hFront, m[v].eigen().h2);
      if (r > 1.2) hFar = std::max(hFar, m[v].eigen().h2);
    }
    EXPECT_GT(hFar, 5 * hFront) << "hgrad " << hgrad;
  }
}

TEST(AdaptMetric, MetricQualityOfEquilateralMeshIsOne) {
  Mesh2 m;
  m.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2)};
  m.triangles = {{0, 1, 2}};
  std::vector<Metric2> metric(3, Metric2::isotropic(1.0));
  EXPECT_NEAR(metricQuality(m, metric).mean, 1.0, 1e-12);
  EXPECT_NEAR(metricQuality(m, metric).min, 1.0, 1e-12);
  // Stretched ×10 along x: poor in the identity metric, perfect in the metric stretched alike.
  for (auto& v : m.vertices) v.x() *= 10;
  EXPECT_LT(metricQuality(m, metric).mean, 0.3);
  std::vector<Metric2> stretched(3, Metric2::fromSizes(10, 1, 0));
  EXPECT_NEAR(metricQuality(m, stretched).mean, 1.0, 1e-12);
  metric.pop_back();
  EXPECT_THROW(metricQuality(m, metric), InputError);
}

// l2Share φ: M_∞(u; (1 − φ) N) ∩ M_2(u; φ N), rescaled to N. p = 2 spreads the density
// (det|H|^(1/3) against √det|H|), so the share moves vertices from the front to the far field
// at the same complexity.
TEST(AdaptMetric, L2ShareKeepsTheComplexityAndMovesDensityToTheFarField) {
  const Mesh2 mesh = fem::unitSquareMesh(50, 0.15, 3);
  const auto u = waveFront(mesh);
  auto densities = [&](double share, double hgrad) {
    AdaptOptions o;
    o.hgrad = hgrad;
    o.l2Share = share;
    const auto m = adaptMetric(mesh, u, 8000, o).metric;
    EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(8000), 1.0, 0.01) << share << " " << hgrad;
    double front = 0, far = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double r = (mesh.vertices[v] + Vec2(0.05, 0.05)).norm(), d = std::sqrt(m[v].det());
      if (std::abs(r - 0.7) < 0.01) front = std::max(front, d);
      if (r > 1.2) far = std::max(far, d);
    }
    return std::pair{front, far};
  };
  for (double hgrad : {0.0, 1.25}) {
    const auto [front0, far0] = densities(0, hgrad);
    const auto [front1, far1] = densities(0.5, hgrad);
    EXPECT_LT(front1, 0.95 * front0) << "hgrad " << hgrad;
    EXPECT_GT(far1, 1.2 * far0) << "hgrad " << hgrad;
  }
  AdaptOptions bad;
  bad.l2Share = 1;
  EXPECT_THROW(validate(bad), InputError);
}

// dualShare φ_z: M(u; (1 − φ_z) N) ∩ M(z; φ_z N), rescaled to N. A u curved in y alone (u_xx = 0)
// lets M(u) stretch along x up to hmax; a dual curved in x bounds that length.
TEST(AdaptMetric, DualShareBoundsTheAnisotropyOfAFlatDirectionAtTheSameComplexity) {
  const Mesh2 mesh = fem::unitSquareMesh(50, 0.15, 3);
  std::vector<double> u(mesh.numVertices()), z(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2& p = mesh.vertices[v];
    u[v] = p.y() * p.y();
    z[v] = p.x() * (1 - p.x()) * p.y() * (1 - p.y());
  }
  AdaptOptions o;
  const auto hu = recoverHessians(mesh, u, o.hessian);
  const auto hz = recoverHessians(mesh, z, o.hessian);
  auto worstAspect = [&](double share, bool withDual) {
    o.dualShare = share;
    const auto m = metricFromRecovered(mesh, hu, 4000, o, {},
                                       withDual ? std::span<const Hessian2>(hz) : std::span<const Hessian2>())
                       .metric;
    EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(4000), 1.0, 0.01) << share;
    double worst = 0;
    for (int v = 0; v < mesh.numVertices(); ++v)
      if ((mesh.vertices[v] - Vec2(0.5, 0.5)).lpNorm<Eigen::Infinity>() < 0.3) {
        const MetricEigen e = m[v].eigen();
        worst = std::max(worst, e.h1 / e.h2);
      }
    return worst;
  };
  const double off = worstAspect(0, true);
  EXPECT_EQ(worstAspect(0.2, false), off);  // no dual Hessians given: no intersection
  EXPECT_GT(off, 300);                      // h_x at hmax (a quarter of the diagonal), h_y from u_yy = 2
  EXPECT_LT(worstAspect(0.05, true), 0.3 * off);
  EXPECT_LT(worstAspect(0.2, true), 0.15 * off);
  std::vector<Hessian2> few(hz.begin(), hz.begin() + 3);
  EXPECT_THROW(metricFromRecovered(mesh, hu, 4000, o, {}, few), InputError);
  AdaptOptions bad;
  bad.dualShare = -0.1;
  EXPECT_THROW(validate(bad), InputError);
  bad.dualShare = 0.5;
  bad.l2Share = 0.5;
  EXPECT_THROW(validate(bad), InputError);
}

TEST(AdaptMetric, LoopDefaultCapLetsAStraightLayerReachHmax) {
  // u = y²: u_xx = 0, so the Hessian sets no long size; the cap on h_long/h_short does. At 10⁷
  // vertices h_y ≈ 10⁻⁵ against hmax = √2/4: the loop's default (10⁵) leaves h_x at hmax, the
  // metric options' own default (10⁴) binds.
  const Mesh2 mesh = fem::unitSquareMesh(30, 0.15, 3);
  std::vector<double> u(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) u[v] = mesh.vertices[v].y() * mesh.vertices[v].y();
  AdaptOptions o;
  o.dualShare = 0;
  const auto hu = recoverHessians(mesh, u, o.hessian);
  auto worstAspect = [&] {
    double worst = 0;
    for (const auto& m : metricFromRecovered(mesh, hu, 1e7, o).metric) {
      const MetricEigen e = m.eigen();
      worst = std::max(worst, e.h1 / e.h2);
    }
    return worst;
  };
  EXPECT_EQ(o.metric.maxAnisotropy, 1e5);
  EXPECT_GT(worstAspect(), 1.5e4);
  o.metric.maxAnisotropy = MetricOptions{}.maxAnisotropy;
  EXPECT_LE(worstAspect(), 1e4 * (1 + 1e-9));
}

TEST(AdaptMetric, DualGoalWeightsTheDualMetricByTheLaplacianOfU) {
  const Mesh2 mesh = fem::unitSquareMesh(50, 0.15, 3);
  std::vector<double> flat(mesh.numVertices()), ramp(mesh.numVertices()), z(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const Vec2& p = mesh.vertices[v];
    flat[v] = p.y() * p.y();                       // Δu = 2 everywhere
    ramp[v] = p.y() * p.y() + std::pow(p.y(), 4);  // u_xx = 0, Δu = 2 + 12y²: u's gradient error grows with y
    z[v] = p.x() * (1 - p.x()) * p.y() * (1 - p.y());
  }
  AdaptOptions o;
  o.dualShare = 0.05;
  const auto hz = recoverHessians(mesh, z, o.hessian);
  auto metric = [&](const std::vector<double>& u, bool goal) {
    o.dualGoal = goal;
    const auto m = metricFromRecovered(mesh, recoverHessians(mesh, u, o.hessian), 4000, o, {}, hz).metric;
    EXPECT_NEAR(metricComplexity(mesh, m) / complexityForVertices(4000), 1.0, 0.01);
    return m;
  };
  // A constant weight changes nothing: the dual's metric is rescaled to its share anyway.
  const auto off = metric(flat, false), on = metric(flat, true);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const double scale = std::abs(off[v].m11()) + std::abs(off[v].m22());
    EXPECT_NEAR(on[v].m11(), off[v].m11(), 1e-9 * scale) << v;
    EXPECT_NEAR(on[v].m12(), off[v].m12(), 1e-9 * scale) << v;
    EXPECT_NEAR(on[v].m22(), off[v].m22(), 1e-9 * scale) << v;
  }
  // Weighted by |Δu|, the dual bounds the long size (x) more where Δu is large (y ≈ 0.8) and less
  // where it is small (y ≈ 0.3) than the unweighted dual does.
  auto aspectAt = [&](const std::vector<Metric2>& m, double y) {
    double worst = 0;
    for (int v = 0; v < mesh.numVertices(); ++v)
      if (std::abs(mesh.vertices[v].y() - y) < 0.05 && std::abs(mesh.vertices[v].x() - 0.5) < 0.2) {
        const MetricEigen e = m[v].eigen();
        worst = std::max(worst, e.h1 / e.h2);
      }
    return worst;
  };
  const auto rampOff = metric(ramp, false), rampOn = metric(ramp, true);
  const double skewOff = aspectAt(rampOff, 0.8) / aspectAt(rampOff, 0.3);
  const double skewOn = aspectAt(rampOn, 0.8) / aspectAt(rampOn, 0.3);
  EXPECT_LT(skewOn, 0.7 * skewOff) << skewOn << " " << skewOff;
}
