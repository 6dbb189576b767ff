#include "ablmg/adapt/transient_loop.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/error_norms.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace ablmg::adapt {
namespace {

/// The time integrator's state on one mesh: u^n and (BDF2) u^(n−1).
struct State {
  Eigen::VectorXd u, previous;  ///< previous empty before the first step
  double dtPrevious = 0;
};

/// Result of solving one interval on one mesh.
struct IntervalSolve {
  State end;
  std::vector<Hessian2> hmax;     ///< ∩ |H| over the sub-steps (when asked)
  std::vector<StepRecord> steps;  ///< errors per step (when asked)
  double seconds = 0, metricSeconds = 0;
};

void requireValidMesh(const Mesh2& mesh, const Domain& domain, const char* what) {
  const MeshValidation v = mesh.validate(domain.area(), 1e-6);
  if (!v.ok) ABLMG_FAIL("transient loop: the " << what << " mesh is not valid: " << v.firstProblem);
}

IntervalSolve solveInterval(const Mesh2& mesh, const fem::TransientProblem& problem, const TransientOptions& o,
                            const State& start, double t0, double dt, int firstStep, int steps, bool hessians,
                            bool errors) {
  IntervalSolve r;
  const Stopwatch clock0;
  double metricSeconds = 0;
  fem::HeatSolver solver(mesh, fem::heatProblem(problem), o.scheme);
  solver.setState(t0, start.u, start.previous.size() ? std::optional<Eigen::VectorXd>(start.previous) : std::nullopt,
                  start.dtPrevious);
  const auto addHessians = [&](const Eigen::VectorXd& u) {
    const Stopwatch c;
    intersectHessians(r.hmax,
                      recoverHessians(mesh, std::span<const double>(u.data(), std::size_t(u.size())), o.adapt.hessian));
    metricSeconds += c.seconds();
  };
  if (hessians) addHessians(start.u);
  for (int j = 1; j <= steps; ++j) {
    solver.step(dt);
    if (hessians && (j % o.hessianEvery == 0 || j == steps)) addHessians(solver.u());
    if (errors) {
      const auto e = fem::computeErrors(mesh, solver.u(), problem.exactAt(solver.time()), o.errorDegree);
      r.steps.push_back({firstStep + j, solver.time(), mesh.numVertices(), e.l2, e.h1});
    }
  }
  r.end = {solver.u(), solver.previous(), solver.dtPrevious()};
  r.metricSeconds = metricSeconds;
  r.seconds = clock0.seconds() - metricSeconds;
  return r;
}

/// The state carried from one mesh to another (both fields of BDF2 at once).
State transferState(const Mesh2& from, const Mesh2& to, const State& s, const TransferOptions& options,
                    TransferStats& stats) {
  std::vector<Eigen::VectorXd> fields{s.u};
  if (s.previous.size()) fields.push_back(s.previous);
  auto out = transferFields(from, to, fields, options, &stats);
  State r;
  r.u = std::move(out[0]);
  if (out.size() > 1) r.previous = std::move(out[1]);
  r.dtPrevious = s.dtPrevious;
  return r;
}

/// The state on `mesh` at the start of `interval`: the exact u(t0) interpolated (interval 0),
/// `state` itself (`sameMesh`), or its transfer from `from`.
State stateOn(const Mesh2& mesh, const Mesh2& from, bool sameMesh, const State& state, int interval,
              const fem::TransientProblem& problem, double t0, const TransferOptions& options, TransferStats& stats) {
  stats = {};
  if (interval == 0) return {fem::interpolate(mesh, [&](double x, double y) { return problem.u(x, y, t0); }), {}, 0};
  if (sameMesh) return state;
  return transferState(from, mesh, state, options, stats);
}

/// The next interval's mesh (see the header): fixed-point passes (Interval) or one remesh from
/// u(t_i) (Current). Fills the record's times and passes; returns the new mesh.
Mesh2 adaptedMesh(const Mesh2& current, const State& state, const fem::TransientProblem& problem,
                  const TransientOptions& o, int interval, double t0, double dt, int steps, IntervalRecord& rec,
                  int& meshes) {
  Mesh2 candidate = current;
  const int passes = o.metric == TransientMetric::Interval ? o.fixedPointIterations : 1;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Hessian2> hmax;
    if (o.metric == TransientMetric::Interval) {
      Stopwatch c;
      TransferStats ts;
      const State start = stateOn(candidate, current, pass == 0, state, interval, problem, t0, o.transfer, ts);
      rec.tTransfer += c.seconds();
      IntervalSolve s = solveInterval(candidate, problem, o, start, t0, dt, 0, steps, true, false);
      rec.tSolve += s.seconds;
      rec.tMetric += s.metricSeconds;
      hmax = std::move(s.hmax);
      ++rec.passes;
    } else {
      const Stopwatch c;
      intersectHessians(
          hmax, recoverHessians(current, std::span<const double>(state.u.data(), state.u.size()), o.adapt.hessian));
      rec.tMetric += c.seconds();
    }
    Stopwatch c;
    std::vector<Metric2> metric = metricFromRecovered(candidate, hmax, o.vertices, o.adapt).metric;
    rec.tMetric += c.seconds();
    c.restart();
    Mesh2 next = remesh(problem.domain, candidate, std::move(metric), o.adapt.mesh).mesh;
    rec.tRemesh += c.seconds();
    requireValidMesh(next, problem.domain, "remeshed");
    ++meshes;
    candidate = std::move(next);
  }
  return candidate;
}

void accumulate(TransientReport& report, const std::vector<StepRecord>& steps, double dt) {
  for (const StepRecord& s : steps) {
    report.spaceTimeL2 += dt * s.l2 * s.l2;
    report.spaceTimeH1 += dt * s.h1 * s.h1;
    report.maxL2 = std::max(report.maxL2, s.l2);
    report.averageVertices += double(s.vertices);
    report.steps.push_back(s);
  }
}

}  // namespace

TransientMetric parseTransientMetric(const std::string& name) {
  if (name == "interval") return TransientMetric::Interval;
  if (name == "current") return TransientMetric::Current;
  ABLMG_REQUIRE(false, "unknown transient metric '" << name << "' (valid: interval, current)");
  return TransientMetric::Interval;
}

std::string toString(TransientMetric m) { return m == TransientMetric::Interval ? "interval" : "current"; }

void validate(const TransientOptions& o, double tStart) {
  ABLMG_REQUIRE(o.remeshEvery >= 1, "transient options: remeshEvery must be >= 1 (got " << o.remeshEvery << ")");
  ABLMG_REQUIRE(o.dt >= 0 && std::isfinite(o.dt), "transient options: dt must be > 0 (got " << o.dt << ")");
  ABLMG_REQUIRE(std::isnan(o.tEnd) || (std::isfinite(o.tEnd) && o.tEnd > tStart),
                "transient options: the final time " << o.tEnd << " must be after the start time " << tStart);
  ABLMG_REQUIRE(std::isfinite(o.vertices) && o.vertices >= 10,
                "transient options: vertices must be >= 10 (got " << o.vertices << ")");
  ABLMG_REQUIRE(o.hessianEvery >= 1, "transient options: hessianEvery must be >= 1 (got " << o.hessianEvery << ")");
  ABLMG_REQUIRE(o.fixedPointIterations >= 1 && o.fixedPointIterations <= 20,
                "transient options: fixedPointIterations must be in 1..20 (got " << o.fixedPointIterations << ")");
  ABLMG_REQUIRE(o.errorDegree >= 1 && o.errorDegree <= 8,
                "transient options: errorDegree must be in 1..8 (got " << o.errorDegree << ")");
  AdaptOptions a = o.adapt;
  a.targetVertices = {o.vertices};
  validate(a);
}

void intersectHessians(std::vector<Hessian2>& accumulated, std::span<const Hessian2> h) {
  ABLMG_REQUIRE(accumulated.empty() || accumulated.size() == h.size(),
                "intersectHessians: " << h.size() << " Hessians for " << accumulated.size() << " accumulated");
  double largest = 0;
  for (const Hessian2& m : h) largest = std::max(largest, m.cwiseAbs().maxCoeff());
  const double floor = std::max(1e-12 * largest, 1e-300);
  const bool first = accumulated.empty();
  if (first) accumulated.resize(h.size());
  for (std::size_t v = 0; v < h.size(); ++v) {
    const Hessian2 a = absoluteHessian(h[v], floor);
    if (first) {
      accumulated[v] = a;
      continue;
    }
    const Metric2 m = intersect(Metric2::raw(a(0, 0), a(0, 1), a(1, 1)),
                                Metric2::raw(accumulated[v](0, 0), accumulated[v](0, 1), accumulated[v](1, 1)));
    accumulated[v] << m.m11(), m.m12(), m.m12(), m.m22();
  }
}

/// At most this many time steps (a typo in dt or the final time would run for days, and
/// overflows the step counter past 2·10⁹).
constexpr double kMaxTimeSteps = 1e6;

TransientReport runTransientLoop(const fem::TransientProblem& problem, const TransientOptions& options,
                                 const std::function<void(const TransientFrame&)>& onInterval) {
  validate(options, problem.tStart);
  const Stopwatch clock0;
  TransientReport report;
  report.dt = options.dt > 0 ? options.dt : problem.dt;
  report.tStart = problem.tStart;
  const double tEnd = std::isnan(options.tEnd) ? problem.tEnd : options.tEnd;
  const double steps = std::ceil((tEnd - problem.tStart) / report.dt - 1e-9);
  ABLMG_REQUIRE(steps <= kMaxTimeSteps, "transient options: (tEnd - tStart) / dt = ("
                                            << tEnd << " - " << problem.tStart << ") / " << report.dt << " = " << steps
                                            << " steps, more than " << kMaxTimeSteps);
  const int nSteps = std::max(1, int(steps));
  report.tEnd = problem.tStart + nSteps * report.dt;
  Mesh2 current = uniformMesh(problem.domain, options.vertices, options.adapt.mesh).mesh;
  requireValidMesh(current, problem.domain, "initial");
  report.meshes = 1;
  State state{fem::interpolate(current, [&](double x, double y) { return problem.u(x, y, problem.tStart); }), {}, 0};
  const int k = options.remeshEvery;
  for (int i = 0, step0 = 0; step0 < nSteps; ++i, step0 += k) {
    const int steps = std::min(k, nSteps - step0);
    const double t0 = problem.tStart + step0 * report.dt;
    IntervalRecord rec;
    rec.interval = i;
    rec.time = t0;
    Mesh2 next = options.uniform
                     ? current
                     : adaptedMesh(current, state, problem, options, i, t0, report.dt, steps, rec, report.meshes);
    const Stopwatch c;
    TransferStats ts;
    const State start = stateOn(next, current, options.uniform, state, i, problem, t0, options.transfer, ts);
    rec.tTransfer += c.seconds();
    rec.massDefect = ts.maxRelativeMassDefect();
    report.maxMassDefect = std::max(report.maxMassDefect, rec.massDefect);
    current = std::move(next);
    rec.vertices = current.numVertices();
    rec.triangles = current.numTriangles();
    rec.l2AtStart = fem::computeErrors(current, start.u, problem.exactAt(t0), options.errorDegree).l2;
    IntervalSolve s = solveInterval(current, problem, options, start, t0, report.dt, step0, steps, false, true);
    rec.tSolve += s.seconds;
    ++rec.passes;
    accumulate(report, s.steps, report.dt);
    state = std::move(s.end);
    rec.timeEnd = report.steps.back().time;
    rec.l2AtEnd = report.steps.back().l2;
    rec.spaceTimeL2 = std::sqrt(report.spaceTimeL2);
    rec.spaceTimeH1 = std::sqrt(report.spaceTimeH1);
    report.intervals.push_back(rec);
    if (onInterval) onInterval(TransientFrame{report.intervals.back(), current, state.u});
  }
  report.spaceTimeL2 = std::sqrt(report.spaceTimeL2);
  report.spaceTimeH1 = std::sqrt(report.spaceTimeH1);
  report.averageVertices /= double(report.steps.size());
  report.seconds = clock0.seconds();
  return report;
}

}  // namespace ablmg::adapt
