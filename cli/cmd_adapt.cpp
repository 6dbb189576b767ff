// ablmg adapt: the adaptive solve loop on a library problem or on a problem of the
// user's own (CONFIG.json: domain, κ, f, boundary data, optionally the exact solution), with reports.
//
//   ablmg adapt (--problem NAME [--param KEY=VALUE ...] | CONFIG.json)
//               (--vertices N [--start-vertices N0] [--growth G] [--passes P] [--passes-up-to N1]
//                | [--cycles K] --target-vertices N1,N2,...)
//               [--p 2|1|inf] [--norm l2|h1] [--shape-blend W] [--hgrad G] [--hessian lsq|double] [--hmin H] [--hmax H]
//               [--hmax-uniform K] [--l2-share F] [--dual-weight G] [--h1-weight G] [--dual-share F]
//               [--dual-goal on|off]
//               [--max-aniso R] [--seed S] [--stop-l2 E] [--stop-h1 E] [--stop-aim A] [--stop-jump J] [--warm-start on|off]
//               [--lattice short|axes|long|auto] [--plateau-gain G] [--saddle-shape S] [--corner-grading B] [--repeat-min-change C] [--uniform on|off] [--vtu on|off] [--medit on|off] [--png on|off] [--out-dir DIR]
//
// NAME is a problem of fem/test_problems.hpp (wavefront, peak, lshape, tanhlayer, ...), KEY one
// of its parameters. --vertices N: the default schedule, from N0 to N geometrically with P passes
// per size below N1 (adapt::geometricSchedule); --target-vertices: cycle k targets N_k vertices
// (the last N repeats when K exceeds the list).
// --p selects the Lp norm the metric is optimal for (default inf, FreeFem/BAMG's L∞ metric: the
// H1-optimal grading at singular points; 2: L2).
// --norm h1 makes its density optimal for the W^{1,p} seminorm of the interpolation error instead
// (p = 2, its default: H1), and --shape-blend W ∈ [0, 1] sets the shape to (|H|/√det|H|)^(1+W)
// (0 the Lp shape, 1 the H1 shape |H|², which loses on meshes whose elements are not oriented
// along |H|: adapt/metric_from_hessian.hpp) keeping the norm's density; the default W is the
// loop's 0.05 for both norms.
//
// Writes DIR/convergence.csv (the header kCsvHeader, more columns after it, one row per
// cycle), DIR/convergence.json (options, rows, fitted rates), DIR/cycle_K.vtu (mesh, u_h,
// exact u, nodal error, the metric the mesh was built for, per-element errors),
// DIR/convergence.png (errors vs N, log-log, slopes −1/2 and −1, and uniform structured meshes
// of the same N when --uniform on) and DIR/final_mesh.png (not with --png off); with --medit on also
// DIR/cycle_K.mesh and DIR/cycle_K_metric.sol (the metric computed on mesh K for mesh K+1,
// tensor m11 m12 m22). Prints the resolved options, one `Cycle k:` line per cycle, the rates.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/convergence.hpp"
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/cli/progress_line.hpp"
#include "ablmg/cli/config.hpp"
#include "ablmg/cli/mesh_output.hpp"
#include "ablmg/cli/problem_config.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/fem/material_problems.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <tuple>

namespace ablmg::cli {
namespace {

constexpr const char* kCsvHeader =
    "cycle,vertices,triangles,l2_error,h1_error,l2_interp_error,q_mean,q_min,t_solve,t_recover,t_metric,t_mesh";

struct Args {
  std::string config;   ///< CONFIG.json (a problem of the user's own), or
  std::string problem;  ///< --problem NAME
  std::map<std::string, double> params;
  adapt::AdaptOptions options;
  double finalVertices = 0;  ///< --vertices N: the default schedule (adapt::geometricSchedule)
  adapt::ScheduleOptions schedule;
  std::string outDir = "adapt_out";
  bool uniform = true, vtu = true, medit = false;
  bool png = true;            ///< --png off: no convergence.png and final_mesh.png (runs that are timed or batched)
  int verbosity = 1;          ///< -v N: 0 = no progress line
  bool printOptions = false;  ///< --print-options: print the options in effect and exit
  /// --reference-vertices N: errors against the loop's own solution at N vertices (problems
  /// without an exact solution); < 0: the default (4 × the last target for a material problem,
  /// none otherwise); 0: none.
  double referenceVertices = -1;
};

/// The parser's state: the arguments, the position in them, and which options were given (some
/// defaults depend on others: --norm h1 picks its own p unless it is given).
struct ArgCursor {
  const std::vector<std::string>& args;
  std::size_t i = 0;
  bool haveTargets = false, pGiven = false;
  const std::string& key() const { return args[i]; }
  const std::string& value() {
    ABLMG_REQUIRE(i + 1 < args.size(), "adapt: " << args[i] << " needs a value");
    return args[++i];
  }
  double number(Infinity inf = Infinity::Refused) {
    const std::string name = "adapt: " + args[i];
    return parseNumber(value(), name, inf);
  }
  /// The value as a number in [lo, hi], named in the error.
  double numberIn(double lo, double hi) {
    const std::string name = args[i];
    const double v = number();
    ABLMG_REQUIRE(v >= lo && v <= hi, "adapt: " << name << " must be in [" << lo << ", " << hi << "], got " << v);
    return v;
  }
  /// The value as an integer in [lo, hi], named in the error.
  int integerIn(int lo, int hi) {
    const std::string name = args[i];
    const double v = number();
    ABLMG_REQUIRE(v >= lo && v <= hi && v == std::floor(v),
                  "adapt: " << name << " must be an integer in " << lo << ".." << hi << ", got " << v);
    return int(v);
  }
};

/// The problem and the schedule: --problem --param --cycles --target-vertices --vertices
/// --start-vertices --growth --passes --passes-up-to. False if `c.key()` is none of them.
bool parseScheduleOption(ArgCursor& c, Args& a) {
  const std::string& key = c.key();
  if (key == "--problem") {
    a.problem = c.value();
  } else if (key == "--param") {
    const std::string kv = c.value();
    const auto eq = kv.find('=');
    ABLMG_REQUIRE(eq != std::string::npos && eq > 0, "adapt: --param expects KEY=VALUE, got '" << kv << "'");
    a.params[kv.substr(0, eq)] = parseNumber(kv.substr(eq + 1), "adapt: --param " + kv.substr(0, eq));
  } else if (key == "--cycles") {
    a.options.cycles = c.integerIn(1, 1000);
  } else if (key == "--target-vertices") {
    a.options.targetVertices.clear();
    std::stringstream ss(c.value());
    std::string item;
    while (std::getline(ss, item, ','))
      a.options.targetVertices.push_back(parseNumber(item, "adapt: --target-vertices"));
    c.haveTargets = true;
  } else if (key == "--vertices") {
    a.finalVertices = c.number();
    ABLMG_REQUIRE(a.finalVertices > 0, "adapt: --vertices must be > 0, got " << a.finalVertices);
  } else if (key == "--start-vertices") {
    a.schedule.startVertices = c.number();
  } else if (key == "--growth") {
    a.schedule.growth = c.number();
  } else if (key == "--passes") {
    a.schedule.passes = c.integerIn(1, 20);
  } else if (key == "--passes-up-to") {
    a.schedule.passesUpTo = c.number();
  } else {
    return false;
  }
  return true;
}

/// The metric: --p --norm --shape-blend --hgrad --hessian --hmin --hmax --hmax-uniform
/// --max-aniso --dual-weight --h1-weight --dual-share --dual-goal --l2-share --saddle-shape --corner-grading.
/// False if `c.key()` is none of them.
bool parseMetricOption(ArgCursor& c, Args& a) {
  const std::string& key = c.key();
  auto& metric = a.options.metric;
  if (key == "--p") {
    metric.p = c.number(Infinity::Allowed);
    c.pGiven = true;
  } else if (key == "--norm") {
    metric.norm = adapt::parseErrorNorm(c.value());
    // --norm h1 keeps the loop's shape blend (0.05): the H1 shape (--shape-blend 1) stretches
    // elements by (λ1/λ2)² and had 1.2-8x the H1 error of the blend at 4·10³ vertices on the
    // library, errors rising with N on the line singularity and the layer (docs/config.md).
    // Without --p: p = 2, the H1 seminorm itself (the default p = inf would make it W^{1,inf},
    // whose grading h ~ r^{4/3} crowds the vertices into a corner singularity)
    if (metric.norm == adapt::ErrorNorm::H1 && !c.pGiven) metric.p = 2;
  } else if (key == "--shape-blend") {
    metric.shapeBlend = c.number();
  } else if (key == "--hgrad") {
    a.options.hgrad = c.number();
  } else if (key == "--hessian") {
    a.options.hessian = adapt::parseHessianMethod(c.value());
  } else if (key == "--hmin") {
    metric.hmin = c.number();
  } else if (key == "--hmax") {
    metric.hmax = c.number(Infinity::Allowed);
  } else if (key == "--hmax-uniform") {
    metric.hmaxUniform = c.number(Infinity::Allowed);
  } else if (key == "--max-aniso") {
    metric.maxAnisotropy = c.number();
  } else if (key == "--dual-weight") {
    a.options.dualWeight = c.number();
  } else if (key == "--h1-weight") {
    a.options.h1Weight = c.number();
  } else if (key == "--dual-share") {
    a.options.dualShare = c.number();
  } else if (key == "--dual-goal") {
    a.options.dualGoal = parseOnOff(c.value(), "adapt: --dual-goal");
  } else if (key == "--l2-share") {
    a.options.l2Share = c.number();
  } else if (key == "--saddle-shape") {
    metric.saddleShape = c.numberIn(0, 1);
  } else if (key == "--corner-grading") {
    a.options.cornerGrading = c.numberIn(0, 1);
  } else {
    return false;
  }
  return true;
}

/// The loop and its mesher: --seed --stop-l2 --stop-h1 --stop-aim --stop-jump --warm-start
/// --repeat-min-change --plateau-gain --lattice. False if `c.key()` is none of them.
bool parseLoopOption(ArgCursor& c, Args& a) {
  const std::string& key = c.key();
  auto& placement = a.options.mesh.placement;
  if (key == "--seed") {
    placement.seed = std::uint64_t(parseInteger(c.value(), "adapt: --seed", 0, std::numeric_limits<long long>::max()));
  } else if (key == "--stop-l2" || key == "--stop-h1") {
    const double e = c.number();
    ABLMG_REQUIRE(e > 0 && std::isfinite(e), "adapt: " << key << " must be a positive error, got " << e);
    (key == "--stop-l2" ? a.options.stopL2 : a.options.stopH1) = e;
  } else if (key == "--stop-aim") {
    const double v = c.number();
    ABLMG_REQUIRE(v >= 0 && v <= 1, "adapt: --stop-aim must be in [0, 1] (0: off), got " << v);
    a.options.stopSizeAim = v;
  } else if (key == "--stop-jump") {
    a.options.stopJump = c.numberIn(0, 100);
  } else if (key == "--warm-start") {
    a.options.warmStart = parseOnOff(c.value(), "adapt: --warm-start");
  } else if (key == "--repeat-min-change") {
    a.options.repeatMinChange = a.options.stopRepeatMinChange = c.numberIn(0, 10);
  } else if (key == "--plateau-gain") {
    const double g = c.number();
    ABLMG_REQUIRE(g >= 0 && g < 1, "adapt: --plateau-gain must be in [0, 1), got " << g);
    placement.plateauSteps = g > 0 ? 10 : 0;
    placement.plateauGain = g;
  } else if (key == "--lattice") {
    placement.lattice.orientation = mesher::parseLatticeOrientation(c.value());
  } else {
    return false;
  }
  return true;
}

/// The outputs: --uniform --vtu --medit --png -v --out-dir --print-options --reference-vertices.
/// False if `c.key()` is none of them.
bool parseOutputOption(ArgCursor& c, Args& a) {
  const std::string& key = c.key();
  if (key == "--uniform") {
    a.uniform = parseOnOff(c.value(), "adapt: --uniform");
  } else if (key == "--vtu") {
    a.vtu = parseOnOff(c.value(), "adapt: --vtu");
  } else if (key == "--medit") {
    a.medit = parseOnOff(c.value(), "adapt: --medit");
  } else if (key == "--png") {
    a.png = parseOnOff(c.value(), "adapt: --png");
  } else if (key == "-v") {
    a.verbosity = int(parseInteger(c.value(), "adapt: -v", 0, 10));
  } else if (key == "--out-dir") {
    a.outDir = c.value();
  } else if (key == "--print-options") {
    a.printOptions = true;
  } else if (key == "--reference-vertices") {
    a.referenceVertices = c.number();
    ABLMG_REQUIRE(a.referenceVertices == 0 || (a.referenceVertices >= 10 && a.referenceVertices <= 1e9),
                  "adapt: --reference-vertices must be 0 (none) or in [10, 1e9], got " << a.referenceVertices);
  } else {
    return false;
  }
  return true;
}

Args parseArgs(const std::vector<std::string>& args) {
  Args a;
  ArgCursor c{args};
  for (; c.i < args.size(); ++c.i) {
    const std::string& key = c.key();
    if (parseScheduleOption(c, a) || parseMetricOption(c, a) || parseLoopOption(c, a) || parseOutputOption(c, a))
      continue;
    if (!key.empty() && key[0] != '-') {
      ABLMG_REQUIRE(a.config.empty(), "adapt: more than one config file ('" << a.config << "', '" << key << "')");
      a.config = key;
    } else {
      ABLMG_REQUIRE(
          false,
          "adapt: unknown argument '"
              << key
              << "' (valid: --problem --param --vertices --start-vertices --growth --passes "
                 "--passes-up-to --cycles --target-vertices --p --norm --shape-blend --hgrad "
                 "--hessian --hmin --hmax --hmax-uniform --l2-share --dual-weight --h1-weight "
                 "--dual-share --dual-goal --max-aniso --seed "
                 "--stop-l2 --stop-h1 --stop-aim --stop-jump --warm-start --lattice --saddle-shape --corner-grading "
                 "--repeat-min-change "
                 "--plateau-gain --uniform --vtu --medit --png --reference-vertices --out-dir --print-options)");
    }
  }
  ABLMG_REQUIRE(a.problem.empty() != a.config.empty() || (a.printOptions && a.problem.empty()),
                "adapt: give either --problem NAME or CONFIG.json (see ablmg adapt --help)");
  ABLMG_REQUIRE(a.config.empty() || a.params.empty(),
                "adapt: --param is for --problem NAME; a config gives \"params\"");
  ABLMG_REQUIRE(c.haveTargets || a.finalVertices > 0 || a.printOptions,
                "adapt: --vertices N (the default schedule) or --target-vertices N1,N2,... is required");
  ABLMG_REQUIRE(!(c.haveTargets && a.finalVertices > 0), "adapt: give --vertices N or --target-vertices, not both");
  if (a.finalVertices > 0) a.options.targetVertices = adapt::geometricSchedule(a.finalVertices, a.schedule);
  adapt::validate(a.options);
  return a;
}

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

/// P1 errors on a structured mesh of the problem's domain with about `n` vertices.
struct UniformPoint {
  double vertices, l2, h1;
};
UniformPoint uniformRun(const adapt::AdaptProblem& p, double n) {
  const auto [lo, hi] = p.domain.boundingBox();
  const double boxArea = (hi - lo).prod(), fill = p.domain.area() / boxArea;
  const int cells = std::max(2, int(std::lround(std::sqrt(n / fill))) - 1);
  Mesh2 mesh;
  try {
    mesh = fem::structuredMesh(p.domain, cells, cells);
  } catch (const InputError&) {  // corners off the grid: the smallest even multiple that fits
    mesh = fem::structuredMesh(p.domain, 2 * ((cells + 1) / 2), 2 * ((cells + 1) / 2));
  }
  const auto sol = fem::solvePoisson(mesh, p.pde);
  const auto err = fem::computeErrors(mesh, sol.u, *p.exact);
  return {double(mesh.numVertices()), err.l2, err.h1};
}

/// The problem the loop runs, with what the reports say about it.
struct Problem {
  adapt::AdaptProblem data;
  std::string name;     ///< library name, or the config file
  nlohmann::json echo;  ///< {"u": formula, "params": ...} or the config's problem object
};

Problem libraryProblem(const std::string& name, const std::map<std::string, double>& params) {
  const auto materials = fem::materialProblemNames();
  if (std::find(materials.begin(), materials.end(), name) != materials.end()) {
    const fem::MaterialProblem p = fem::makeMaterialProblem(name, params);
    return {adapt::adaptProblem(p), p.name, {{"pde", p.description}, {"params", p.params}}};
  }
  const fem::TestProblem p = fem::makeProblem(name, params);
  return {adapt::adaptProblem(p), p.name, {{"u", p.formula}, {"params", p.params}}};
}

/// CONFIG.json: {"domain": {...} (as in docs/config.md; only for an expression problem),
/// "problem": name or {kappa, f, dirichlet, neumann, exact} (cli/problem_config.hpp), "params"}.
Problem configProblem(const std::string& path) {
  const nlohmann::json config = readJsonFile(path);
  requireKeys(config, path, {"domain", "problem", "params"});
  ABLMG_REQUIRE(config.contains("problem"),
                path << ": problem: missing (a library name or {\"f\": ..., \"dirichlet\": ...})");
  ProblemSetup setup = problemFromJson(config, path);
  Problem p;
  p.name = setup.domain ? config["problem"].get<std::string>() : path;
  p.echo = setup.echo;
  if (setup.domain) {
    ABLMG_REQUIRE(!config.contains("domain"), path << ": domain: a library problem has its own domain");
    p.data.domain = *setup.domain;
  } else {
    ABLMG_REQUIRE(config.contains("domain"), path << ": domain: missing (needed for an expression problem)");
    p.data.domain = parseDomainJson(config["domain"], path, std::filesystem::path(path).parent_path().string());
  }
  p.data.pde = std::move(setup.problem);
  if (setup.exact.u) p.data.exact = std::move(setup.exact);
  return p;
}

/// True when structuredMesh can grid the domain (axis-parallel sides, no slits).
bool uniformFits(const Domain& domain) {
  if (domain.hasSlits()) return false;
  for (const auto& loop : domain.loops())
    for (std::size_t k = 0; k < loop.points.size(); ++k) {
      const Vec2 d = loop.points[(k + 1) % loop.points.size()] - loop.points[k];
      if (d.x() != 0 && d.y() != 0) return false;
    }
  return true;
}

/// The loop's options as the JSON report gives them ("options").
nlohmann::json loopOptionsJson(const Args& a, int cycles) {
  return {{"target_vertices", a.options.targetVertices},
          {"cycles", cycles},

          {"hessian", adapt::toString(a.options.hessian)},
          {"p", std::isinf(a.options.metric.p) ? nlohmann::json("inf") : nlohmann::json(a.options.metric.p)},
          {"norm", adapt::toString(a.options.metric.norm)},
          {"shape_blend",
           a.options.metric.shapeBlend ? nlohmann::json(*a.options.metric.shapeBlend) : nlohmann::json(nullptr)},
          {"hmin", a.options.metric.hmin},
          {"hmax", std::isinf(a.options.metric.hmax) ? nlohmann::json("inf") : nlohmann::json(a.options.metric.hmax)},
          {"max_anisotropy", a.options.metric.maxAnisotropy},
          {"hgrad", a.options.hgrad},
          {"hmax_uniform", std::isinf(a.options.metric.hmaxUniform) ? nlohmann::json("inf")
                                                                    : nlohmann::json(a.options.metric.hmaxUniform)},
          {"l2_share", a.options.l2Share},
          {"dual_weight", a.options.dualWeight},
          {"h1_weight", a.options.h1Weight},
          {"dual_share", a.options.dualShare},
          {"dual_goal", a.options.dualGoal},
          {"warm_start", a.options.warmStart},
          {"repeat_min_change", a.options.repeatMinChange},
          {"stop_repeat_min_change", a.options.stopRepeatMinChange},
          {"stop_l2", a.options.stopL2},
          {"stop_h1", a.options.stopH1},
          {"stop_aim", a.options.stopSizeAim},
          {"stop_jump", a.options.stopJump},
          {"saddle_shape", a.options.metric.saddleShape},
          {"corner_grading", a.options.cornerGrading},
          {"lattice", mesher::latticeOrientationName(a.options.mesh.placement.lattice.orientation)},
          {"plateau_gain", a.options.mesh.placement.plateauSteps > 0 ? a.options.mesh.placement.plateauGain : 0.0},
          {"seed", a.options.mesh.placement.seed}};
}

const char* kAdaptHelp =
    R"(usage: ablmg adapt (--problem NAME [--param KEY=VALUE ...] | CONFIG.json)
                   (--vertices N [--start-vertices N0] [--growth G] [--passes P] [--passes-up-to N1]
                    | [--cycles K] --target-vertices N1,N2,...)
                   [--p 2|1|inf] [--norm l2|h1] [--shape-blend W] [--hgrad G] [--hessian lsq|double]
                   [--hmin H] [--hmax H] [--hmax-uniform K] [--l2-share F] [--dual-weight G] [--h1-weight G] [--dual-share F]
                   [--dual-goal on|off]
                   [--max-aniso R] [--seed S] [--stop-l2 E] [--stop-h1 E] [--stop-aim A] [--stop-jump J] [--warm-start on|off]
                   [--lattice short|axes|long|auto]
                   [--plateau-gain G] [--saddle-shape S] [--corner-grading B] [--repeat-min-change C] [--uniform on|off]
                   [--vtu on|off]
                   [--medit on|off]
                   [--out-dir DIR] [-v N]
                   [--reference-vertices N] [--print-options]

The adaptive loop (solve -> errors -> Hessian recovery -> metric -> remesh) on a problem of
fem/test_problems.hpp (wavefront, peak, lshape, tanhlayer, ...) or on CONFIG.json's own:
  {"domain": {...as for ablmg mesh...},
   "problem": {"kappa": "1", "f": "expr", "dirichlet": {"1": "expr", "default": "expr"},
               "neumann": {"2": "expr"}, "exact": {"u": "expr", "ux": "expr", "uy": "expr"}}}
(expressions in x, y; tags as the domain's; "exact" optional: without it the only error figure
is est=, the L2 interpolation error estimated from the recovered Hessian; examples/configs/adapt_*.json).
Material problems (fem/material_problems.hpp: battery) have a kappa and f per subdomain and no
exact solution: their errors are against a reference solution, the loop's own at
--reference-vertices N vertices (default 4x the last target; 0 = none; also for a CONFIG.json
without "exact"). The final mesh's interfaces are checked to lie on chains of its edges.
--vertices N: from N0 (default 400) to N by the factor G (default 2), P passes (default 3) at
each size below N1 (default 10000); --target-vertices: cycle k targets N_k vertices (the last N
repeats when K exceeds the list). Writes DIR/convergence.csv/.json/.png,
DIR/final_mesh.png (--png, default on), DIR/cycle_K.vtu (--vtu), DIR/cycle_K.mesh +
cycle_K_metric.sol (--medit).
Metric flags: docs/config.md ("ablmg adapt"); formulas: adapt/metric_from_hessian.hpp.
--stop-l2 E, --stop-h1 E: stop after the first cycle whose error (against the exact solution)
is at most E; N (--vertices) is then the most the run may use. With a stop, after each size
the next one is chosen from the errors of the last two sizes (log-log, the optimal rate where
the fit is steeper) to reach A x E (--stop-aim A, default 0.95; 0 = off: whole sizes of the
schedule) when that is below the schedule's next size, so the run does not overshoot the
target by a whole size; when it is beyond the next size but within J x the current one
(--stop-jump J, default 16; <= 1 = off), the run goes there directly.
--saddle-shape S: on near-harmonic saddles (indefinite Hessians) a shape of aspect up to 3^(S/2)
at 45 degrees to the eigenvectors, meshed as right isosceles triangles by lattice rows the
metric carries per vertex (default 1; 0 = off; adapt/metric_from_hessian.hpp). At boundary
vertices the side (+-45 degrees) whose long axis runs along the wall.
--corner-grading B: at reentrant corners of the boundary where the sizes around shrink like r^s towards
it (a singular point), the corner's size becomes B times the end r* of that grading, at most
a quarter per remesh (default 0.25; 0 = off; adapt/metric_from_hessian.hpp, gradeSingularCorners).
--repeat-min-change C: a size's remaining passes are skipped after a cycle whose next metric
differs from the one its mesh was built for by less than C (dM= in the cycle lines: the mean
largest log change of a unit edge's length; 0 = run every pass; default 0, and 0.2 with
--stop-l2/--stop-h1, where only the last cycle's error counts; adapt/adaptive_loop.hpp).
--lattice: the initial bubble lattice has one row along each node's short-size direction
(short, the default here), the x axis's image (axes), the long-size direction (long), or
short only where the metric is stretched (auto: h1/h2 >= 16; axes where <= 8).
--plateau-gain G: placement stops once the share of bubble pairs within 10 % of unit metric
length gains less than G in 10 steps (default 0.01, as ablmg remesh; 0 = run to the residual
or stall rule: ~1/3 more remesh time, errors a few % lower; adapt/adaptive_loop.hpp).
-v N: 0 = no progress line on stderr (shown on a terminal only; default 1); >= 2 also the mesher's stage
times for each cycle's mesh.
--print-options: print the options in effect (JSON: the loop's and the mesher's, the "adapt"
preset with the flags above applied) and exit; the problem and the schedule may be omitted.
)";

/// The problem with the reference solution as its "exact" one when it has none of its own and
/// --reference-vertices (or the material problems' default) asks for one; returns the reference
/// mesh's vertex count (0: none).
long attachReferenceSolution(const Args& a, Problem& problem) {
  const double referenceVertices =
      a.referenceVertices >= 0 ? a.referenceVertices
      : problem.data.regions.numTriangles() > 0 && !problem.data.exact
          ? 4 * *std::max_element(a.options.targetVertices.begin(), a.options.targetVertices.end())
          : 0.0;
  ABLMG_REQUIRE(referenceVertices == 0 || !problem.data.exact,
                "adapt: --reference-vertices is for a problem without an exact solution");
  if (referenceVertices <= 0) return 0;
  std::cout << "ablmg adapt: reference solution: the loop to " << referenceVertices << " vertices" << std::endl;
  adapt::AdaptOptions ro = a.options;
  ProgressLine referenceProgress("reference", a.verbosity);
  ro.progress = referenceProgress.callback();
  adapt::ReferenceSolution ref = adapt::referenceSolution(problem.data, referenceVertices, ro);
  referenceProgress.clear();
  problem.data.exact = std::move(ref.exact);
  problem.echo["reference_vertices"] = ref.vertices;
  return ref.vertices;
}

void printResolvedOptions(const Args& a, const Problem& problem, long referenceMeshVertices) {
  std::cout << "ablmg adapt: problem " << problem.name << ": " << problem.echo.dump();
  if (!problem.data.exact) std::cout << "\n  no exact solution: errors are not computed (NaN in the reports)";
  if (referenceMeshVertices > 0)
    std::cout << "\n  errors against the reference solution on " << referenceMeshVertices
              << " vertices (not an exact solution: meaningful while N is well below it)";
  std::cout << "\n  cycles " << (a.options.cycles > 0 ? a.options.cycles : int(a.options.targetVertices.size()))
            << ", target vertices";
  for (double n : a.options.targetVertices) std::cout << " " << n;
  std::cout << "\n  hessian " << adapt::toString(a.options.hessian) << ", p " << a.options.metric.p << ", norm "
            << adapt::toString(a.options.metric.norm) << ", shape blend "
            << (a.options.metric.shapeBlend ? fmt("%g", *a.options.metric.shapeBlend) : std::string("default"))
            << ", hmin " << a.options.metric.hmin << ", hmax " << a.options.metric.hmax << ", max anisotropy "
            << a.options.metric.maxAnisotropy << ", hgrad "
            << (a.options.hgrad > 1 ? fmt("%g", a.options.hgrad) : "off") << ", lattice "
            << mesher::latticeOrientationName(a.options.mesh.placement.lattice.orientation) << ", seed "
            << a.options.mesh.placement.seed << "\n  output " << a.outDir << "\n";
}

/// The `Cycle k:` line; with -v 2 also the mesher's stage times.
void printCycle(const adapt::CycleReport& r, bool exact, int verbosity) {
  std::printf("Cycle %d: N=%ld T=%ld", r.cycle, r.vertices, r.triangles);
  if (exact) std::printf(" L2=%.3e H1=%.3e L2interp=%.3e", r.l2, r.h1, r.l2Interp);
  std::printf(" est=%.3e", r.l2InterpEstimate);
  if (std::isfinite(r.metricChange)) std::printf(" dM=%.3f", r.metricChange);
  std::printf(
      " q=%.3f/%.3f  t: solve %.2fs (assembly %.2f ordering %.2f factor %.2f) errors %.2fs recover %.2fs "
      "metric %.2fs mesh %.2fs\n",
      r.qMean, r.qMin, r.tSolve, r.tAssembly, r.tOrdering, r.tFactor, r.tErrors, r.tRecover, r.tMetric, r.tMesh);
  if (verbosity >= 2) {
    const auto& p = r.meshStats.placement;
    std::printf(
        "  mesh %d: placement %.2fs (initial %.2f, dynamics %.2f in %d steps%s, adjacency %.2f, population "
        "%.2f: +%ld -%ld), connection %.2fs, quality post-pass %.2fs (q min %.3f -> %.3f, %ld swaps, %ld "
        "moves, %ld collapses), validation %.2fs\n",
        r.cycle, p.secondsInitial + p.secondsDynamics + p.secondsAdjacency + p.secondsPopulation, p.secondsInitial,
        p.secondsDynamics, p.steps,
        p.qualityPlateau ? " (quality plateau)"
        : p.stalled      ? " (stalled)"
        : p.hitStepCap   ? " (step cap)"
                         : "",
        p.secondsAdjacency, p.secondsPopulation, p.inserted, p.deleted,
        r.meshStats.connect.secondsLocalMeshes + r.meshStats.connect.secondsRepair, r.meshStats.improve.seconds,
        r.meshStats.improve.qMinBefore, r.meshStats.improve.qMinAfter, long(r.meshStats.improve.swaps),
        long(r.meshStats.improve.moves), long(r.meshStats.improve.collapses), r.meshStats.secondsValidate);
  }
  std::fflush(stdout);
}

/// DIR/cycle_K.vtu (mesh, u_h, exact u and nodal error, per-element errors, metric, quality) and,
/// with --medit on, DIR/cycle_K.mesh + DIR/cycle_K_metric.sol (the metric for the next cycle).
void writeCycleFiles(const Args& a, const Problem& problem, const adapt::CycleData& c) {
  namespace fs = std::filesystem;
  const std::string stem = (fs::path(a.outDir) / ("cycle_" + std::to_string(c.report.cycle))).string();
  if (a.vtu) {
    const int n = c.mesh.numVertices();
    io::Field uh{"u", 1, std::vector<double>(c.u.data(), c.u.data() + n)}, ue{"u_exact", 1, {}}, err{"error", 1, {}};
    std::vector<io::Field> points{uh}, cells;
    if (problem.data.exact) {
      for (int v = 0; v < n; ++v) {
        ue.values.push_back(problem.data.exact->u(c.mesh.vertices[v].x(), c.mesh.vertices[v].y()));
        err.values.push_back(ue.values.back() - uh.values[v]);
      }
      points.push_back(ue);
      points.push_back(err);
      cells.push_back({"l2_error", 1, c.errors.elementL2});
      if (!c.errors.elementH1.empty()) cells.push_back({"h1_error", 1, c.errors.elementH1});
    }
    for (auto& f : io::metricFields(c.meshMetric)) points.push_back(std::move(f));
    auto quality = qualityFields(c.mesh, c.meshMetric);
    for (auto& f : quality.point) points.push_back(std::move(f));
    for (auto& f : quality.cell) cells.push_back(std::move(f));
    io::writeVtu(stem + ".vtu", c.mesh, points, cells);
  }
  if (a.medit) {  // as MMG/FreeFem++ read them
    io::writeMesh(stem + ".mesh", c.mesh);
    if (!c.nextMetric.empty()) io::writeSol(stem + "_metric.sol", c.nextMetric);
  }
}

/// How much of the materials' interfaces the final mesh leaves off its interface edges.
struct InterfaceCheck {
  double uncovered = 0, length = 0;
};

/// Rates, the error check, and (with materials) the interface check, on stdout.
InterfaceCheck printSummary(const adapt::AdaptReport& report, const Problem& problem, const Mesh2& finalMesh) {
  const bool exact = problem.data.exact.has_value();
  // A fit over cycles of one size has no slope (NaN): "n/a", as null in convergence.json.
  const auto rate = [](double r) {
    if (!std::isfinite(r)) return std::string("n/a");
    char s[32];
    std::snprintf(s, sizeof s, "%.3f", r);
    return std::string(s);
  };
  if (exact) {
    std::printf("Rates (log-log fit over the last %d cycles, optimal P1: L2 -1, H1 -0.5): L2 %s  H1 %s  L2interp %s\n",
                report.rateWindow, rate(report.l2Rate).c_str(), rate(report.h1Rate).c_str(),
                rate(report.l2InterpRate).c_str());
    std::printf("Errors decrease from the first to the last cycle: %s\n", report.errorsDecrease ? "yes" : "NO");
  }
  std::printf("Estimated interpolation error (recovered Hessian, est=): rate %s over the last %d cycles%s\n",
              rate(report.l2InterpEstimateRate).c_str(), report.rateWindow,
              exact ? "; compare L2interp" : " (optimal P1: -1)");
  if (report.stoppedEarly) std::printf("Stopped after cycle %d: error target reached\n", report.cycles.back().cycle);
  InterfaceCheck check;
  const Mesh2& regions = problem.data.regions;
  if (regions.numTriangles() == 0) return check;
  check.uncovered = adapt::uncoveredInterfaceLength(regions, finalMesh);
  for (const auto& e : regions.interfaceEdges)
    check.length += (regions.vertices[std::size_t(e.b)] - regions.vertices[std::size_t(e.a)]).norm();
  std::printf("Interfaces in the final mesh: %.3g of their length %.4g not on final interface edges (%s)\n",
              check.uncovered, check.length, check.uncovered <= 1e-9 * check.length ? "resolved" : "NOT RESOLVED");
  return check;
}

nlohmann::json finiteOrNull(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void writeCsv(const std::string& path, const adapt::AdaptReport& report) {
  io::writeFileAtomically(path, [&](std::ostream& os) {
    os << kCsvHeader
       << ",target_vertices,max_vertex_error,predicted_vertices,l2_interp_estimate,t_assembly,t_ordering,t_factor,"
          "t_errors\n";
    os.precision(10);
    for (const auto& r : report.cycles)
      os << r.cycle << ',' << r.vertices << ',' << r.triangles << ',' << r.l2 << ',' << r.h1 << ',' << r.l2Interp << ','
         << r.qMean << ',' << r.qMin << ',' << r.tSolve << ',' << r.tRecover << ',' << r.tMetric << ',' << r.tMesh
         << ',' << r.targetVertices << ',' << r.maxVertex << ',' << r.predictedVertices << ',' << r.l2InterpEstimate
         << ',' << r.tAssembly << ',' << r.tOrdering << ',' << r.tFactor << ',' << r.tErrors << '\n';
  });
}

/// convergence.json without the uniform comparison (compareWithUniform adds it).
nlohmann::json reportJson(const Args& a, const Problem& problem, const adapt::AdaptReport& report,
                          const InterfaceCheck& interfaces) {
  const auto num = finiteOrNull;
  nlohmann::json j;
  j["problem"] = problem.name;
  j["definition"] = problem.echo;
  if (!a.config.empty()) j["config"] = a.config;
  j["options"] = loopOptionsJson(a, int(report.cycles.size()));
  for (const auto& r : report.cycles)
    j["cycles"].push_back({{"cycle", r.cycle},
                           {"vertices", r.vertices},
                           {"triangles", r.triangles},
                           {"target_vertices", r.targetVertices},
                           {"l2_error", num(r.l2)},
                           {"h1_error", num(r.h1)},
                           {"l2_interp_error", num(r.l2Interp)},
                           {"l2_interp_estimate", r.l2InterpEstimate},
                           {"max_vertex_error", num(r.maxVertex)},
                           {"q_mean", r.qMean},
                           {"q_min", r.qMin},
                           {"t_solve", r.tSolve},
                           {"t_assembly", r.tAssembly},
                           {"t_ordering", r.tOrdering},
                           {"t_factor", r.tFactor},
                           {"t_errors", r.tErrors},
                           {"t_recover", r.tRecover},
                           {"t_metric", r.tMetric},
                           {"t_mesh", r.tMesh}});
  j["rates"] = {{"window", report.rateWindow},
                {"l2", num(report.l2Rate)},
                {"h1", num(report.h1Rate)},
                {"l2_interp", num(report.l2InterpRate)},
                {"l2_interp_estimate", num(report.l2InterpEstimateRate)}};
  j["errors_decrease"] = report.errorsDecrease;
  if (problem.data.regions.numTriangles() > 0)
    j["interfaces"] = {{"length", interfaces.length}, {"uncovered", interfaces.uncovered}};
  j["stopped_early"] = report.stoppedEarly;
  return j;
}

/// The adaptive curves of the plot: errors per cycle against N.
std::vector<io::Curve> errorCurves(const adapt::AdaptReport& report, bool exact) {
  std::vector<io::Curve> curves;
  if (exact) curves = {{"adaptive L2", {}, {}}, {"adaptive H1", {}, {}}, {"adaptive L2 interpolant", {}, {}}};
  curves.push_back({"estimated L2 interpolant", {}, {}});
  for (const auto& r : report.cycles) {
    for (auto& c : curves) c.x.push_back(double(r.vertices));
    if (exact) {
      curves[0].y.push_back(r.l2);
      curves[1].y.push_back(r.h1);
      curves[2].y.push_back(r.l2Interp);
    }
    curves.back().y.push_back(r.l2InterpEstimate);
  }
  return curves;
}

/// Structured meshes of the cycles' target sizes, solved: their errors go into the JSON
/// ("uniform", and "uniform_match": how many times fewer vertices the adaptive curve needs for
/// the finest uniform mesh's errors) and as two curves into the plot.
void compareWithUniform(const Problem& problem, const adapt::AdaptReport& report, nlohmann::json& j,
                        std::vector<io::Curve>& curves) {
  if (problem.data.regions.numTriangles() > 0) {
    std::printf("Uniform: skipped (the problem has subdomains, which a uniform grid does not follow)\n");
    return;
  }
  if (!uniformFits(problem.data.domain)) {
    std::printf("Uniform: skipped (the domain is not a union of grid cells: sides not axis-parallel, or slits)\n");
    return;
  }
  io::Curve ul{"uniform L2", {}, {}}, uh{"uniform H1", {}, {}};
  for (const auto& r : report.cycles) {
    if (!ul.x.empty() && std::abs(r.targetVertices - report.cycles[std::size_t(r.cycle) - 1].targetVertices) < 0.5)
      continue;
    UniformPoint u{};
    try {
      u = uniformRun(problem.data, r.targetVertices);
    } catch (const InputError& e) {  // corners off every grid tried (a hole's corner at x = 0.3 of [0, 2])
      std::printf("Uniform: skipped from N=%.0f on (%s)\n", r.targetVertices, e.what());
      break;
    }
    ul.x.push_back(u.vertices);
    ul.y.push_back(u.l2);
    uh.x.push_back(u.vertices);
    uh.y.push_back(u.h1);
    j["uniform"].push_back({{"vertices", u.vertices}, {"l2_error", u.l2}, {"h1_error", u.h1}});
    std::printf("Uniform: N=%.0f L2=%.3e H1=%.3e\n", u.vertices, u.l2, u.h1);
  }
  if (ul.x.empty()) return;
  curves.push_back(ul);
  curves.push_back(uh);
  std::vector<double> an, al2, ah1;  // log–log interpolation along the cycles
  for (const auto& r : report.cycles)
    if (r.vertices > 0 && r.l2 > 0 && r.h1 > 0 && std::isfinite(r.l2) && std::isfinite(r.h1)) {
      an.push_back(double(r.vertices));
      al2.push_back(r.l2);
      ah1.push_back(r.h1);
    }
  for (const auto& [name, uniformCurve, adaptiveErrors] : {std::tuple{"h1", &uh, &ah1}, std::tuple{"l2", &ul, &al2}}) {
    const double nu = uniformCurve->x.back(), eu = uniformCurve->y.back();
    const double na = an.empty() ? std::nan("") : adapt::verticesToReach(an, *adaptiveErrors, eu);
    j["uniform_match"][name] = {{"uniform_vertices", nu},
                                {"uniform_error", eu},
                                {"adaptive_vertices", finiteOrNull(na)},
                                {"ratio", finiteOrNull(nu / na)}};
    if (std::isfinite(na))
      std::printf(
          "Finest uniform mesh (N=%.0f, %s=%.3e) matched by the adaptive curve at N=%.0f: %.1fx fewer vertices\n", nu,
          name, eu, na, nu / na);
    else
      std::printf("Finest uniform mesh (N=%.0f, %s=%.3e) not matched by the adaptive curve\n", nu, name, eu);
  }
}

/// convergence.png (when every estimate is positive) and final_mesh.png (materials in colour);
/// returns whether the plot was drawn.
bool writePictures(const Args& a, const Problem& problem, const std::vector<io::Curve>& curves,
                   const Mesh2& finalMesh) {
  namespace fs = std::filesystem;
  const bool plottable = std::all_of(curves.back().y.begin(), curves.back().y.end(), [](double e) { return e > 0; });
  if (plottable)
    io::drawLogLogPlot((fs::path(a.outDir) / "convergence.png").string(), curves, {-0.5, -1.0}, "vertices N", "error",
                       "ablmg adapt: " + problem.name);
  const std::string meshPng = (fs::path(a.outDir) / "final_mesh.png").string();
  if (problem.data.regions.numTriangles() > 0) {  // the materials in colour, their interfaces in red
    const std::vector<double> material(finalMesh.triangleRefs.begin(), finalMesh.triangleRefs.end());
    io::drawMesh(meshPng, finalMesh, material, "material");
  } else {
    io::drawMesh(meshPng, finalMesh);
  }
  return plottable;
}

int runAdapt(const std::vector<std::string>& argv) {
  for (const auto& x : argv)
    if (x == "-h" || x == "--help") {
      std::cout << kAdaptHelp;
      return 0;
    }
  Args a = parseArgs(argv);
  if (a.printOptions) {
    printEffectiveOptions("adapt", "adapt", a.options.mesh, loopOptionsJson(a, int(a.options.targetVertices.size())));
    return 0;
  }
  // 0. The problem, and a reference solution where it has no exact one.
  Problem problem = a.config.empty() ? libraryProblem(a.problem, a.params) : configProblem(a.config);
  const long referenceMeshVertices = attachReferenceSolution(a, problem);
  const bool exact = problem.data.exact.has_value();
  namespace fs = std::filesystem;
  fs::create_directories(a.outDir);
  // 1. Resolved options.
  printResolvedOptions(a, problem, referenceMeshVertices);
  // 2. The loop; each cycle prints its line and writes its files.
  Mesh2 finalMesh;
  ProgressLine progress("adapt", a.verbosity);
  a.options.progress = progress.callback();
  const adapt::AdaptReport report = adapt::runAdaptiveLoop(problem.data, a.options, [&](const adapt::CycleData& c) {
    progress.clear();
    printCycle(c.report, exact, a.verbosity);
    writeCycleFiles(a, problem, c);
    if (c.nextMetric.empty()) finalMesh = c.mesh;
  });
  progress.clear();
  // 3. Rates and checks; 4. the reports; 5. uniform refinement on the same axes, the pictures.
  const InterfaceCheck interfaces = printSummary(report, problem, finalMesh);
  writeCsv((fs::path(a.outDir) / "convergence.csv").string(), report);
  nlohmann::json j = reportJson(a, problem, report, interfaces);
  std::vector<io::Curve> curves = errorCurves(report, exact);
  if (a.uniform && exact) compareWithUniform(problem, report, j, curves);
  io::writeFileAtomically((fs::path(a.outDir) / "convergence.json").string(),
                          [&](std::ostream& os) { os << j.dump(2) << "\n"; });
  const bool plottable = a.png && writePictures(a, problem, curves, finalMesh);
  std::cout << "Wrote " << a.outDir << "/convergence.csv, convergence.json" << (plottable ? ", convergence.png" : "")
            << (a.png ? ", final_mesh.png" : "") << (a.vtu ? ", cycle_*.vtu" : "") << "\n";
  return 0;
}

}  // namespace

ABLMG_COMMAND("adapt", "adaptive solve loop (library problem or CONFIG.json): solve, recover, metric, remesh", runAdapt)

}  // namespace ablmg::cli
