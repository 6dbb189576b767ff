#include "ablmg/adapt/adaptive_loop.hpp"

#include "ablmg/adapt/convergence.hpp"
#include "ablmg/adapt/dual_weight.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/core/stopwatch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <tuple>

namespace ablmg::adapt {
void validate(const AdaptOptions& o) {
  ABLMG_REQUIRE(!o.targetVertices.empty(), "adapt options: targetVertices is empty");
  for (std::size_t k = 0; k < o.targetVertices.size(); ++k)
    ABLMG_REQUIRE(std::isfinite(o.targetVertices[k]) && o.targetVertices[k] >= 10,
                  "adapt options: targetVertices[" << k << "] must be >= 10 (got " << o.targetVertices[k] << ")");
  ABLMG_REQUIRE(o.cycles >= 0, "adapt options: cycles must be >= 0 (got " << o.cycles << ")");
  ABLMG_REQUIRE(o.hgrad <= 0 || (o.hgrad > 1 && std::isfinite(o.hgrad)),
                "adapt options: hgrad must be > 1 (or <= 0 for no gradation), got " << o.hgrad);
  ABLMG_REQUIRE(o.l2Share >= 0 && o.l2Share < 1, "adapt options: l2Share must be in [0, 1) (got " << o.l2Share << ")");
  ABLMG_REQUIRE(o.cornerGrading >= 0 && o.cornerGrading <= 1,
                "adapt options: cornerGrading must be in [0, 1] (got " << o.cornerGrading << ")");
  ABLMG_REQUIRE(o.dualShare >= 0 && o.l2Share + o.dualShare < 1,
                "adapt options: dualShare must be >= 0 with l2Share + dualShare < 1 (got " << o.dualShare << " and "
                                                                                           << o.l2Share << ")");
  ABLMG_REQUIRE(o.dualWeight >= 0 && std::isfinite(o.dualWeight),
                "adapt options: dualWeight must be >= 0 (got " << o.dualWeight << ")");
  ABLMG_REQUIRE(o.h1Weight >= 0 && std::isfinite(o.h1Weight),
                "adapt options: h1Weight must be >= 0 (got " << o.h1Weight << ")");
  ABLMG_REQUIRE(o.repeatMinChange >= 0 && o.stopRepeatMinChange >= 0 && std::isfinite(o.stopRepeatMinChange),
                "adapt options: repeatMinChange and stopRepeatMinChange must be >= 0 (got "
                    << o.repeatMinChange << " and " << o.stopRepeatMinChange << ")");
  ABLMG_REQUIRE(std::isfinite(o.stopSizeAim) && o.stopSizeAim <= 1,
                "adapt options: stopSizeAim must be <= 1 (<= 0: off), got " << o.stopSizeAim);
  ABLMG_REQUIRE(std::isfinite(o.stopJump) && o.stopJump >= 0 && o.stopJump <= 100,
                "adapt options: stopJump must be in [0, 100] (<= 1: off), got " << o.stopJump);
  ABLMG_REQUIRE(o.errorDegree >= 1 && o.errorDegree <= 8,
                "adapt options: errorDegree must be in 1..8 (got " << o.errorDegree << ")");
  MetricOptions m = o.metric;
  m.targetVertices = o.targetVertices.front();
  validate(m);
}

std::vector<double> geometricSchedule(double finalVertices, const ScheduleOptions& o) {
  ABLMG_REQUIRE(std::isfinite(finalVertices) && finalVertices >= 10 && finalVertices <= 1e9,
                "adapt schedule: final vertices must be in [10, 1e9] (got " << finalVertices << ")");
  ABLMG_REQUIRE(std::isfinite(o.startVertices) && o.startVertices >= 10,
                "adapt schedule: startVertices must be >= 10 (got " << o.startVertices << ")");
  ABLMG_REQUIRE(std::isfinite(o.growth) && o.growth > 1.01 && o.growth <= 100,
                "adapt schedule: growth must be in (1.01, 100] (got " << o.growth << ")");
  ABLMG_REQUIRE(o.passes >= 1 && o.passes <= 20, "adapt schedule: passes must be in 1..20 (got " << o.passes << ")");
  // Backwards from N by the growth factor, so that the last steps have the full ratio; the
  // first size lies in [N_0, growth · N_0) (or is N itself when N ≤ N_0).
  const int steps = finalVertices > o.startVertices
                        ? int(std::floor(std::log(finalVertices / o.startVertices) / std::log(o.growth) + 1e-9))
                        : 0;
  std::vector<double> sizes;
  for (int k = steps; k >= 1; --k) sizes.push_back(std::round(finalVertices / std::pow(o.growth, k)));
  sizes.push_back(finalVertices);
  std::vector<double> out;
  for (double n : sizes)
    for (int k = 0; k < (n < o.passesUpTo ? o.passes : 1); ++k) out.push_back(n);
  return out;
}

mesher::MeshResult uniformMesh(const Domain& domain, double targetVertices, const mesher::MeshOptions& options) {
  ABLMG_REQUIRE(targetVertices > 0, "uniformMesh: targetVertices must be > 0 (got " << targetVertices << ")");
  const double h = std::sqrt(domain.area() / complexityForVertices(targetVertices));
  return mesher::meshDomain(domain, ConstantMetricField(Metric2::isotropic(h)), options);
}

mesher::MeshResult uniformMesh(const AdaptProblem& problem, double targetVertices, const mesher::MeshOptions& options) {
  if (problem.regions.numTriangles() == 0) return uniformMesh(problem.domain, targetVertices, options);
  ABLMG_REQUIRE(targetVertices > 0, "uniformMesh: targetVertices must be > 0 (got " << targetVertices << ")");
  const double h = std::sqrt(problem.domain.area() / complexityForVertices(targetVertices));
  return remesh(problem.domain, problem.regions,
                std::vector<Metric2>(problem.regions.vertices.size(), Metric2::isotropic(h)), options);
}

AdaptProblem adaptProblem(const fem::TestProblem& problem) {
  return {problem.domain, problem.poisson(), problem.exact(), {}};
}

AdaptProblem adaptProblem(const fem::MaterialProblem& problem) {
  return {problem.domain, problem.pde, std::nullopt, problem.regions};
}

AdaptReport runAdaptiveLoop(const fem::TestProblem& problem, const AdaptOptions& options,
                            const std::function<void(const CycleData&)>& onCycle) {
  return runAdaptiveLoop(adaptProblem(problem), options, onCycle);
}

namespace {
/// What the unit-load dual of dual_weight.hpp gives the next metric: the density factor
/// (options.dualWeight) and the dual's recovered Hessians (options.dualShare); each empty when off
/// or when the problem has no Dirichlet boundary (the unit-load dual would have no solution).
struct DualCorrection {
  std::vector<double> scale;
  std::vector<Hessian2> hessians;
  std::unique_ptr<fem::Factorisation> factor;  ///< in: u's, for the dual's solve (same A); freed by recoverWithDual
};
bool hasDual(const fem::PoissonProblem& problem) { return !problem.dirichlet.empty() || problem.hasDirichletDefault; }
/// u's recovered Hessians and, with `withMetric` (not the last cycle), the correction of the next
/// metric: the H1 weight's density factor, and when the dual is used (dualWeight, dualShare) the
/// unit-load dual solved (its wall seconds in `tDual`) and, with dualShare, recovered with u in
/// one pass (recoverHessians of two fields: the patches and their QR shared, the same Hessians).
/// The dual has u's matrix: d.factor (u's factorisation) solves it without a second one.
std::vector<Hessian2> recoverWithDual(const Mesh2& mesh, const Eigen::VectorXd& u, const fem::PoissonProblem& problem,
                                      bool withMetric, const AdaptOptions& options, DualCorrection& d, double& tDual) {
  std::unique_ptr<fem::Factorisation> factor = std::move(d.factor);  // freed on return, whatever the path
  const std::span<const double> uv(u.data(), std::size_t(u.size()));
  tDual = 0;
  if (!withMetric) return recoverHessians(mesh, uv, options.hessian);
  const double dualWeight = hasDual(problem) ? options.dualWeight : 0.0;
  if (dualWeight <= 0 && (options.dualShare <= 0 || !hasDual(problem))) {
    if (options.h1Weight > 0) d.scale = densityWeightScale(mesh, uv, {}, 0, options.h1Weight);
    return recoverHessians(mesh, uv, options.hessian);
  }
  const Stopwatch watch;
  const fem::PoissonSolution z = fem::solvePoisson(mesh, unitLoadDual(problem), options.solve, factor);
  tDual = watch.seconds();
  const std::span<const double> zv(z.u.data(), std::size_t(z.u.size()));
  if (dualWeight > 0 || options.h1Weight > 0) d.scale = densityWeightScale(mesh, uv, zv, dualWeight, options.h1Weight);
  if (!(options.dualShare > 0)) return recoverHessians(mesh, uv, options.hessian);
  auto both = recoverHessians(mesh, uv, zv, options.hessian);
  d.hessians = std::move(both[1]);
  return std::move(both[0]);
}
void requireMeshIndependent(const AdaptProblem& p) {
  const auto check = [](const fem::ScalarData& d, const std::string& what) {
    ABLMG_REQUIRE(!d.isVertexValues(), "adaptive loop: " << what
                                                         << " is given per vertex; the loop needs a function or "
                                                            "a constant (the mesh changes every cycle)");
  };
  check(p.pde.kappa, "kappa");
  check(p.pde.f, "f");
  for (const auto& [ref, d] : p.pde.kappaBySubdomain) check(d, "the kappa of subdomain " + std::to_string(ref));
  for (const auto& [ref, d] : p.pde.fBySubdomain) check(d, "the f of subdomain " + std::to_string(ref));
  check(p.pde.dirichletDefault, "the default Dirichlet data");
  for (const auto& [tag, d] : p.pde.dirichlet) check(d, "the Dirichlet data of tag " + std::to_string(tag));
  for (const auto& [tag, d] : p.pde.neumann) check(d, "the Neumann data of tag " + std::to_string(tag));
  ABLMG_REQUIRE(!p.exact || p.exact->u, "adaptive loop: the exact solution has no u");
}

/// The interior vertices of `mesh` (the warm-start seeds of the next placement).
std::vector<Vec2> interiorVertices(const Mesh2& mesh) {
  std::vector<char> onBoundary(std::size_t(mesh.numVertices()), 0);
  for (const auto& e : mesh.boundaryEdges) onBoundary[std::size_t(e.a)] = onBoundary[std::size_t(e.b)] = 1;
  std::vector<Vec2> seeds;
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (!onBoundary[std::size_t(v)]) seeds.push_back(mesh.vertices[std::size_t(v)]);
  return seeds;
}

/// options.mesh for building mesh_k, its progress reports tagged with the cycle and passed on
/// to options.progress (after options.mesh.progress, if any).
mesher::MeshOptions cycleMeshOptions(const AdaptOptions& options, int cycle, int cycles) {
  mesher::MeshOptions m = options.mesh;
  if (options.progress)
    m.progress = [&options, cycle, cycles](Progress p) {
      if (options.mesh.progress) options.mesh.progress(p);
      p.cycle = cycle;
      p.cycles = cycles;
      options.progress(p);
    };
  return m;
}

}  // namespace

double metricChange(std::span<const Metric2> from, std::span<const Metric2> to) {
  ABLMG_REQUIRE(from.size() == to.size(),
                "metricChange: " << from.size() << " and " << to.size() << " metrics (equal counts required)");
  if (from.empty()) return 0;
  double sum = 0;
  for (std::size_t v = 0; v < from.size(); ++v) {
    const Metric2& a = from[v];
    const Metric2& b = to[v];
    // det(b − μ a) = 0: det(a) μ² − (a11 b22 + a22 b11 − 2 a12 b12) μ + det(b) = 0.
    const double da = a.det(), db = b.det();
    const double t = (a.m11() * b.m22() + a.m22() * b.m11() - 2 * a.m12() * b.m12()) / da;
    const double disc = std::sqrt(std::max(0.0, 0.25 * t * t - db / da));
    const double mu1 = 0.5 * t + disc, mu2 = std::max(0.5 * t - disc, 1e-300);
    sum += 0.5 * std::max(std::abs(std::log(mu1)), std::abs(std::log(mu2)));
  }
  return sum / double(from.size());
}

namespace {

/// Reports the loop's own stage of cycle k (solve, recover, metric) on mesh_k.
void reportStage(const AdaptOptions& options, const char* stage, int cycle, int cycles, long vertices) {
  if (options.progress) options.progress({.stage = stage, .nodes = vertices, .cycle = cycle, .cycles = cycles});
}
/// The threshold of repeatsToSkip: repeatMinChange, or with a stop criterion and
/// repeatMinChange 0, stopRepeatMinChange.
double repeatThreshold(const AdaptOptions& o) {
  return o.repeatMinChange > 0 || !(o.stopL2 > 0 || o.stopH1 > 0) ? o.repeatMinChange : o.stopRepeatMinChange;
}

/// Where the schedule goes on after position s: the last repeat of target(s) (so that the next
/// cycle is the next size) when target(s + 1) repeats target(s) and the metric changed by less
/// than repeatThreshold(options); s otherwise. The last size's repeats are never skipped past
/// the schedule's end (the last position stays the last cycle).
int repeatsToSkip(const AdaptOptions& options, const std::vector<double>& targets, int s, double change) {
  const double threshold = repeatThreshold(options);
  if (!(threshold > 0) || !(change < threshold)) return s;
  const int cycles = int(targets.size());
  int j = s;
  while (j + 1 < cycles && targets[std::size_t(j) + 1] == targets[std::size_t(s)]) ++j;
  // Skip to the last repeat only when a larger size follows; otherwise keep one more pass at
  // this, the final, size so that the loop still ends on a mesh adapted at it.
  return j + 1 < cycles ? j : s;
}

/// One target per cycle: options.targetVertices, the last repeated up to options.cycles.
std::vector<double> cycleTargets(const AdaptOptions& options) {
  std::vector<double> targets = options.targetVertices;
  if (options.cycles > 0) targets.resize(std::size_t(options.cycles), options.targetVertices.back());
  return targets;
}

/// AdaptOptions::stopSizeAim: when cycle `row` is the last pass of its size (position s of
/// `targets`), the next size and its passes become the predicted size for the stop criteria
/// if that is below the schedule's next size; when those passes end the schedule, its final
/// size follows them (for a miss). `cycles`: the rows before `row`. Without a stop criterion
/// (stopL2, stopH1 ≤ 0) nothing changes.
void aimAtStop(const AdaptOptions& options, const std::vector<CycleReport>& cycles, const CycleReport& row,
               std::vector<double>& targets, int s) {
  const std::size_t next = std::size_t(s) + 1;
  if (!(options.stopSizeAim > 0) || next >= targets.size() || targets[next] == targets[std::size_t(s)]) return;
  // The previous size's last pass: the latest earlier row of another target.
  const CycleReport* previous = nullptr;
  for (auto it = cycles.rbegin(); it != cycles.rend() && !previous; ++it)
    if (it->targetVertices != row.targetVertices) previous = &*it;
  if (!previous) return;
  double size = 0;
  bool predicted = false;
  for (const auto& [stop, e0, e1, rate] : {std::tuple{options.stopL2, previous->l2, row.l2, -1.0},
                                           std::tuple{options.stopH1, previous->h1, row.h1, -0.5}}) {
    if (!(stop > 0)) continue;
    const double n =
        verticesForError(double(previous->vertices), e0, double(row.vertices), e1, options.stopSizeAim * stop, rate);
    if (!std::isfinite(n)) return;  // one criterion cannot be predicted: keep the schedule
    size = std::max(size, n);
    predicted = true;
  }
  size = std::round(std::max(size, 1.1 * double(row.vertices)));
  if (!predicted) return;
  const double old = targets[next];
  std::size_t j = next;
  if (size < old) {
    for (; j < targets.size() && targets[j] == old; ++j) targets[j] = size;
    if (j == targets.size()) targets.push_back(old);
    return;
  }
  // Beyond the next size: jump there when it is within stopJump × N and a scheduled size at
  // least as large follows (kept for a miss); the skipped sizes go, their first one's passes
  // are run at the new size.
  if (!(size <= options.stopJump * double(row.vertices))) return;
  while (j < targets.size() && targets[j] < size) ++j;
  if (j == targets.size()) return;
  std::size_t passes = 0;
  while (next + passes < j && targets[next + passes] == old) ++passes;
  targets.erase(targets.begin() + std::ptrdiff_t(next), targets.begin() + std::ptrdiff_t(j));
  targets.insert(targets.begin() + std::ptrdiff_t(next), passes, size);
}

/// The convergence curve (the last cycle of each target size) and its log-log rates over the
/// last rateWindow (≤ 4) points; NaN where they cannot be fitted (fewer than 2 distinct sizes,
/// no exact solution for the errors, a non-positive estimate).
void fitRates(AdaptReport& report, bool exact) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int n = int(report.cycles.size());
  // The convergence curve: the last cycle of each target size.
  std::vector<double> nv, l2, h1, li, le;
  for (int k = 0; k < n; ++k) {
    const auto& c = report.cycles[std::size_t(k)];
    if (k + 1 < n && report.cycles[std::size_t(k) + 1].targetVertices == c.targetVertices) continue;
    nv.push_back(double(c.vertices));
    l2.push_back(c.l2);
    h1.push_back(c.h1);
    li.push_back(c.l2Interp);
    le.push_back(c.l2InterpEstimate);
  }
  const int points = int(nv.size());
  report.rateWindow = std::min(4, points);
  report.l2Rate = report.h1Rate = report.l2InterpRate = report.l2InterpEstimateRate = kNaN;
  bool distinct = false;
  for (int i = points - report.rateWindow + 1; i < points; ++i)
    distinct = distinct || nv[i] != nv[points - report.rateWindow];
  const bool positive = std::all_of(le.end() - report.rateWindow, le.end(), [](double e) { return e > 0; });
  if (points >= 2 && distinct && positive) report.l2InterpEstimateRate = logLogSlope(nv, le, report.rateWindow);
  if (points >= 2 && distinct && exact) {
    report.l2Rate = logLogSlope(nv, l2, report.rateWindow);
    report.h1Rate = logLogSlope(nv, h1, report.rateWindow);
    report.l2InterpRate = logLogSlope(nv, li, report.rateWindow);
  }
  report.errorsDecrease = n >= 2 && report.cycles.back().l2 < report.cycles.front().l2 &&
                          report.cycles.back().h1 < report.cycles.front().h1;
}
}  // namespace

double verticesForError(double n0, double e0, double n1, double e1, double target, double optimalRate) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (const double x : {n0, e0, n1, e1, target})
    if (!(x > 0) || !std::isfinite(x)) return kNaN;
  if (!(n0 < n1) || !(optimalRate < 0)) return kNaN;
  const double rate = std::max(std::log(e1 / e0) / std::log(n1 / n0), optimalRate);
  if (!(rate < -0.05)) return kNaN;
  return n1 * std::pow(target / e1, 1 / rate);
}

AdaptReport runAdaptiveLoop(const AdaptProblem& problem, const AdaptOptions& options,
                            const std::function<void(const CycleData&)>& onCycle) {
  validate(options);
  requireMeshIndependent(problem);
  ABLMG_REQUIRE(problem.exact || (options.stopL2 <= 0 && options.stopH1 <= 0),
                "adapt options: stopL2/stopH1 need the exact solution, and this problem has none");
  // The schedule, one target per cycle; aimAtStop may lower its sizes and add a cycle.
  std::vector<double> targets = cycleTargets(options);
  int cycles = int(targets.size());
  auto target = [&](int k) { return targets[std::size_t(k)]; };
  const fem::PoissonProblem& poisson = problem.pde;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  AdaptReport report;
  Stopwatch watch;
  mesher::MeshResult current = uniformMesh(problem, target(0), cycleMeshOptions(options, 0, cycles));
  double tMesh = watch.seconds();
  // k: the cycle (one solve each); s: its place in the schedule, which skips the repeated
  // passes that repeatMinChange finds unnecessary.
  for (int k = 0, s = 0; s < cycles; ++k, ++s) {
    CycleReport row;
    row.cycle = k;
    row.targetVertices = target(s);
    row.vertices = current.mesh.numVertices();
    row.triangles = current.mesh.numTriangles();
    row.tMesh = tMesh;
    row.predictedVertices = current.stats.placement.predictedNodes;
    row.meshStats = current.stats;
    const auto q = metricQuality(current.mesh, current.metric);
    row.qMean = q.mean;
    row.qMin = q.min;

    reportStage(options, "solve", s, cycles, row.vertices);
    watch.restart();
    DualCorrection dual;  // dual.factor: u's factorisation, kept for the dual's solve
    const fem::PoissonSolution sol = fem::solvePoisson(current.mesh, poisson, options.solve, dual.factor);
    row.tSolve = watch.seconds();
    row.tAssembly = sol.stats.assemblySeconds;
    row.tOrdering = sol.stats.orderingSeconds;
    row.tFactor = sol.stats.solveSeconds - sol.stats.orderingSeconds;
    watch.restart();
    const fem::ErrorReport err = problem.exact
                                     ? fem::computeErrors(current.mesh, sol.u, *problem.exact, options.errorDegree)
                                     : fem::ErrorReport{kNaN, kNaN, kNaN, kNaN, {}, {}};
    row.tErrors = problem.exact ? watch.seconds() : 0.0;
    row.l2 = err.l2;
    row.h1 = err.h1;
    row.l2Interp = err.l2Interp;
    row.maxVertex = err.maxVertex;

    std::vector<Metric2> next;
    std::vector<Vec2> nextRows;
    const bool reached =
        (options.stopL2 > 0 && err.l2 <= options.stopL2) || (options.stopH1 > 0 && err.h1 <= options.stopH1);
    report.stoppedEarly = reached && s + 1 < cycles;
    const bool last = s + 1 == cycles || reached;
    // Recovered Hessians of u (and of the unit-load dual, which the next metric uses; its
    // solve counts in the metric's time).
    reportStage(options, "recover", s, cycles, row.vertices);
    watch.restart();
    double tDual = 0;
    const auto hessians = recoverWithDual(current.mesh, sol.u, poisson, !last, options, dual, tDual);
    row.tRecover = watch.seconds() - tDual;
    row.l2InterpEstimate = estimateInterpolationError(current.mesh, hessians).l2;
    if (!last) {
      reportStage(options, "metric", s, cycles, row.vertices);
      aimAtStop(options, report.cycles, row, targets, s);
      cycles = int(targets.size());
      watch.restart();
      AdaptedMetric a = metricFromRecovered(current.mesh, hessians, target(s + 1), options, dual.scale, dual.hessians);
      row.metricChange = metricChange(current.metric, a.metric);
      const int skipTo = repeatsToSkip(options, targets, s, row.metricChange);
      if (skipTo > s) {
        s = skipTo;
        aimAtStop(options, report.cycles, row, targets, s);
        cycles = int(targets.size());
        if (target(s + 1) != target(s))
          a = metricFromRecovered(current.mesh, hessians, target(s + 1), options, dual.scale, dual.hessians);
      }
      next = std::move(a.metric);
      nextRows = std::move(a.rows);
      row.tMetric = tDual + watch.seconds();  // the dual's solve, the metric (twice when passes are skipped), dM
      row.gradationSweeps = a.gradation.sweeps;
    }
    report.cycles.push_back(row);
    if (onCycle) onCycle(CycleData{report.cycles.back(), current.mesh, current.metric, sol.u, err, next});
    if (last) break;
    watch.restart();
    mesher::MeshOptions meshOptions = cycleMeshOptions(options, s + 1, cycles);
    if (options.warmStart) {
      const std::vector<Vec2> seeds = interiorVertices(current.mesh);
      meshOptions.placement.warmStart.insert(meshOptions.placement.warmStart.end(), seeds.begin(), seeds.end());
    }
    current = remesh(problem.domain, current.mesh, std::move(next), meshOptions, std::move(nextRows));
    tMesh = watch.seconds();
  }

  fitRates(report, problem.exact.has_value());
  return report;
}

}  // namespace ablmg::adapt
