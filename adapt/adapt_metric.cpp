// The mesher-free steps of the loop (adaptive_loop.hpp): metricQuality() and adaptMetric().
// Kept apart from runAdaptiveLoop() so that they link and are tested without the mesher.
#include "ablmg/adapt/adaptive_loop.hpp"

#include "ablmg/core/error.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace ablmg::adapt {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

QualitySummary metricQuality(const Mesh2& mesh, std::span<const Metric2> metrics) {
  ABLMG_REQUIRE(long(metrics.size()) == long(mesh.numVertices()),
                "metricQuality: " << metrics.size() << " metrics for " << mesh.numVertices() << " vertices");
  QualitySummary q;
  if (mesh.numTriangles() == 0) return q;
  q.min = std::numeric_limits<double>::infinity();
  double sum = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Metric2 m = (1.0 / 3.0) * (metrics[tri[0]] + metrics[tri[1]] + metrics[tri[2]]);
    const Vec2 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    const double areaM = 0.5 * cross(b - a, c - a) * std::sqrt(m.det());
    const double l2 = m.squaredLength(b - a) + m.squaredLength(c - b) + m.squaredLength(a - c);
    const double qt = 4 * std::sqrt(3.0) * areaM / l2;
    sum += qt;
    q.min = std::min(q.min, qt);
  }
  q.mean = sum / mesh.numTriangles();
  return q;
}

std::vector<Metric2> adaptMetric(const Mesh2& mesh, std::span<const double> u, double targetVertices,
                                 const AdaptOptions& options, double* tRecover, double* tMetric,
                                 GradationStats* gradation) {
  const auto t0 = Clock::now();
  const auto hessians = recoverHessians(mesh, u, options.hessian);
  if (tRecover) *tRecover = since(t0);
  return metricFromRecovered(mesh, hessians, targetVertices, options, tMetric, gradation);
}

std::vector<Metric2> metricFromRecovered(const Mesh2& mesh, std::span<const Hessian2> hessians, double targetVertices,
                                         const AdaptOptions& options, double* tMetric, GradationStats* gradation) {
  const auto t0 = Clock::now();
  MetricOptions mo = options.metric;
  mo.targetVertices = targetVertices;
  if (!std::isfinite(mo.hmax)) {  // keep a few elements across the domain where H ≈ 0
    Vec2 lo = mesh.vertices.front(), hi = lo;
    for (const auto& p : mesh.vertices) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    mo.hmax = std::max(0.25 * (hi - lo).norm(), 2 * mo.hmin);
  }
  auto metric = metricFromHessians(mesh, hessians, mo);
  if (options.hgrad > 1) {
    GradationOptions go;
    go.hgrad = options.hgrad;
    const auto gs = limitGradation(mesh, metric, go);
    if (gradation) *gradation = gs;
    // Gradation only refines: restore the complexity by a uniform rescale (shape kept).
    const double c = metricComplexity(mesh, metric), target = complexityForVertices(targetVertices);
    const double s = target / c;
    for (auto& m : metric) m = boundMetric(s * m, mo.hmin, mo.hmax, mo.maxAnisotropy);
  }
  if (tMetric) *tMetric = since(t0);
  return metric;
}

}  // namespace ablmg::adapt
