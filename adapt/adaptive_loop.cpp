#include "adapt/adaptive_loop.hpp"

#include "adapt/convergence.hpp"
#include "core/error.hpp"
#include "core/metric_field.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace ablmg::adapt {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
} // namespace

void validate(const AdaptOptions& o) {
  ABLMG_REQUIRE(!o.targetVertices.empty(), "adapt options: targetVertices is empty");
  for (std::size_t k = 0; k < o.targetVertices.size(); ++k)
    ABLMG_REQUIRE(std::isfinite(o.targetVertices[k]) && o.targetVertices[k] >= 10,
                  "adapt options: targetVertices[" << k << "] must be >= 10 (got " << o.targetVertices[k] << ")");
  ABLMG_REQUIRE(o.cycles >= 0, "adapt options: cycles must be >= 0 (got " << o.cycles << ")");
  ABLMG_REQUIRE(o.hgrad <= 0 || (o.hgrad > 1 && std::isfinite(o.hgrad)),
                "adapt options: hgrad must be > 1 (or <= 0 for no gradation), got " << o.hgrad);
  ABLMG_REQUIRE(o.errorDegree >= 1 && o.errorDegree <= 8, "adapt options: errorDegree must be in 1..8 (got " << o.errorDegree << ")");
  MetricOptions m = o.metric;
  m.targetVertices = o.targetVertices.front();
  validate(m);
}

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

mesher::MeshResult uniformMesh(const Domain& domain, double targetVertices, const mesher::MeshOptions& options) {
  ABLMG_REQUIRE(targetVertices > 0, "uniformMesh: targetVertices must be > 0 (got " << targetVertices << ")");
  const double h = std::sqrt(domain.area() / complexityForVertices(targetVertices));
  return mesher::meshDomain(domain, ConstantMetricField(Metric2::isotropic(h)), options);
}

std::vector<Metric2> adaptMetric(const Mesh2& mesh, std::span<const double> u, double targetVertices,
                                 const AdaptOptions& options, double* tRecover, double* tMetric, GradationStats* gradation) {
  auto t0 = Clock::now();
  const auto hessians = recoverHessians(mesh, u, options.hessian);
  if (tRecover) *tRecover = since(t0);
  t0 = Clock::now();
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

mesher::MeshResult remesh(const Domain& domain, const Mesh2& mesh, std::vector<Metric2> metric,
                          const mesher::MeshOptions& options) {
  const BackgroundMetricField field(mesh, std::move(metric));
  return mesher::meshDomain(domain, field, options);
}

AdaptReport runAdaptiveLoop(const fem::TestProblem& problem, const AdaptOptions& options,
                            const std::function<void(const CycleData&)>& onCycle) {
  validate(options);
  const int cycles = options.cycles > 0 ? options.cycles : int(options.targetVertices.size());
  auto target = [&](int k) { return options.targetVertices[std::min<std::size_t>(k, options.targetVertices.size() - 1)]; };
  const fem::PoissonProblem poisson = problem.poisson();
  const fem::ExactSolution exact = problem.exact();

  AdaptReport report;
  auto t0 = Clock::now();
  mesher::MeshResult current = uniformMesh(problem.domain, target(0), options.mesh);
  double tMesh = since(t0);
  for (int k = 0; k < cycles; ++k) {
    CycleReport row;
    row.cycle = k;
    row.targetVertices = target(k);
    row.vertices = current.mesh.numVertices();
    row.triangles = current.mesh.numTriangles();
    row.tMesh = tMesh;
    row.predictedVertices = current.stats.placement.predictedNodes;
    const auto q = metricQuality(current.mesh, current.metric);
    row.qMean = q.mean;
    row.qMin = q.min;

    t0 = Clock::now();
    const fem::PoissonSolution sol = fem::solvePoisson(current.mesh, poisson, options.solve);
    row.tSolve = since(t0);
    const fem::ErrorReport err = fem::computeErrors(current.mesh, sol.u, exact, options.errorDegree);
    row.l2 = err.l2;
    row.h1 = err.h1;
    row.l2Interp = err.l2Interp;
    row.maxVertex = err.maxVertex;

    std::vector<Metric2> next;
    const bool reached = (options.stopL2 > 0 && err.l2 <= options.stopL2) || (options.stopH1 > 0 && err.h1 <= options.stopH1);
    report.stoppedEarly = reached && k + 1 < cycles;
    const bool last = k + 1 == cycles || reached;
    if (!last) {
      GradationStats gs;
      next = adaptMetric(current.mesh, std::span<const double>(sol.u.data(), sol.u.size()), target(k + 1), options,
                         &row.tRecover, &row.tMetric, &gs);
      row.gradationSweeps = gs.sweeps;
    }
    report.cycles.push_back(row);
    if (onCycle) onCycle(CycleData{report.cycles.back(), current.mesh, current.metric, sol.u, err, next});
    if (last) break;
    t0 = Clock::now();
    current = remesh(problem.domain, current.mesh, std::move(next), options.mesh);
    tMesh = since(t0);
  }

  const int n = int(report.cycles.size());
  report.rateWindow = std::min(4, n);
  report.l2Rate = report.h1Rate = report.l2InterpRate = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> nv, l2, h1, li;
  for (const auto& c : report.cycles) {
    nv.push_back(double(c.vertices));
    l2.push_back(c.l2);
    h1.push_back(c.h1);
    li.push_back(c.l2Interp);
  }
  bool distinct = false;
  for (int i = n - report.rateWindow + 1; i < n; ++i) distinct = distinct || nv[i] != nv[n - report.rateWindow];
  if (n >= 2 && distinct) {
    report.l2Rate = logLogSlope(nv, l2, report.rateWindow);
    report.h1Rate = logLogSlope(nv, h1, report.rateWindow);
    report.l2InterpRate = logLogSlope(nv, li, report.rateWindow);
  }
  report.errorsDecrease = n >= 2 && l2.back() < l2.front() && h1.back() < h1.front();
  return report;
}

} // namespace ablmg::adapt
