// The mesher-free steps of the loop (adaptive_loop.hpp): metricQuality() and adaptMetric().
// Kept apart from runAdaptiveLoop(): they run no mesher and are tested on their own.
#include "ablmg/adapt/adaptive_loop.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/quality.hpp"

#include <cmath>
#include <limits>

namespace ablmg::adapt {

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
    const double qt = mesher::triangleQuality(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], m);
    sum += qt;
    q.min = std::min(q.min, qt);
  }
  q.mean = sum / mesh.numTriangles();
  return q;
}

AdaptedMetric adaptMetric(const Mesh2& mesh, std::span<const double> u, double targetVertices,
                          const AdaptOptions& options) {
  Stopwatch watch;
  const auto hessians = recoverHessians(mesh, u, options.hessian);
  const double secondsRecover = watch.seconds();
  AdaptedMetric r = metricFromRecovered(mesh, hessians, targetVertices, options);
  r.secondsRecover = secondsRecover;
  return r;
}

namespace {
/// m ← boundMetric(s m) at every vertex; each vertex its own, so the same bits on any team size.
void rescaleAndBound(std::vector<Metric2>& metric, double s, const MetricOptions& mo) {
  constexpr long kMinParallelVertices = 4096;  // below: one thread (a team's wake-up costs more)
  const long n = long(metric.size());
  ParallelFailure failure;
#pragma omp parallel for schedule(static) if (n >= kMinParallelVertices)
  for (long v = 0; v < n; ++v)
    failure.run(v, [&] {
      auto& m = metric[std::size_t(v)];
      m = boundMetric(s * m, mo.hmin, mo.hmax, mo.maxAnisotropy);
    });
  failure.rethrow();
}
}  // namespace

AdaptedMetric metricFromRecovered(const Mesh2& mesh, std::span<const Hessian2> hessians, double targetVertices,
                                  const AdaptOptions& options, std::span<const double> densityScale,
                                  std::span<const Hessian2> dualHessians) {
  ABLMG_REQUIRE(
      densityScale.empty() || long(densityScale.size()) == long(mesh.numVertices()),
      "metricFromRecovered: " << densityScale.size() << " density factors for " << mesh.numVertices() << " vertices");
  ABLMG_REQUIRE(
      dualHessians.empty() || long(dualHessians.size()) == long(mesh.numVertices()),
      "metricFromRecovered: " << dualHessians.size() << " dual Hessians for " << mesh.numVertices() << " vertices");
  Stopwatch watch;
  AdaptedMetric r;
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
  auto& metric = r.metric;
  const bool dual = options.dualShare > 0 && !dualHessians.empty();
  mo.targetVertices = (1 - options.l2Share - (dual ? options.dualShare : 0.0)) * targetVertices;
  metric = metricFromHessians(mesh, hessians, mo);
  if (options.l2Share > 0) {  // ∩ M_2(u; φ N)
    MetricOptions m2 = mo;
    m2.p = 2;
    m2.targetVertices = options.l2Share * targetVertices;
    metric = intersectFields(metric, metricFromHessians(mesh, hessians, m2));
  }
  if (dual) {  // ∩ M(z; φ_z N): the dual's own metric, same norm and bounds
    MetricOptions mz = mo;
    mz.targetVertices = options.dualShare * targetVertices;
    std::span<const Hessian2> hz = dualHessians;
    std::vector<Hessian2> weighted;
    if (options.dualGoal) {  // |Δu_h| |H_z|: the dual's curvature where u's gradient error is
      weighted.assign(dualHessians.begin(), dualHessians.end());
      for (std::size_t v = 0; v < weighted.size(); ++v) weighted[v] *= std::abs(hessians[v].trace());
      hz = weighted;
    }
    metric = intersectFields(metric, metricFromHessians(mesh, hz, mz));
  }
  mo.targetVertices = targetVertices;
  mo.hmax = effectiveHmax(mesh, mo);
  if (options.hgrad > 1 || options.l2Share > 0 || dual) {
    if (options.hgrad > 1) {
      GradationOptions go;
      go.hgrad = options.hgrad;
      r.gradation = limitGradation(mesh, metric, go);
    }
    // Gradation only refines: restore the complexity by a uniform rescale (shape kept).
    const double c = metricComplexity(mesh, metric), target = complexityForVertices(targetVertices);
    const double s = target / c;
    rescaleAndBound(metric, s, mo);
  }
  if (!densityScale.empty()) {  // √det(s M) = s √det M: s scales the density; rescaled to N
    for (std::size_t v = 0; v < metric.size(); ++v) metric[v] = densityScale[v] * metric[v];
    const double s = complexityForVertices(targetVertices) / metricComplexity(mesh, metric);
    rescaleAndBound(metric, s, mo);
  }
  // Singular corners last, after the rescales, then graded again: their few extra vertices are not
  // counted, since the complexity integral (per triangle, area × the mean of the vertices' √det M)
  // would count the corner's size over the whole of its large background triangles, where the
  // mesher's log-Euclidean interpolation of the metric spends a few dozen vertices, and shrink the
  // rest of the mesh for them (AdaptOptions::cornerGrading has the measurements).
  if (options.cornerGrading > 0 && gradeSingularCorners(mesh, metric, options.cornerGrading, mo.hmin) > 0 &&
      options.hgrad > 1) {
    GradationOptions go;
    go.hgrad = options.hgrad;
    limitGradation(mesh, metric, go);
  }
  if (mo.saddleShape > 0) r.rows = saddleLatticeRows(hessians, mo, wallTangents(mesh));
  r.secondsMetric = watch.seconds();
  return r;
}

}  // namespace ablmg::adapt
