// ablmg mesh CONFIG.json -o OUT.{mesh,vtu,png} [--bubbles-only] [--report R.json] [--seed N] [--max-nodes N]
//
// Reads the JSON configuration (docs/config.md), prints every option in effect, meshes the
// domain with ablmg::mesher::meshDomain (or only places the bubbles), writes the outputs
// atomically and prints a one-line summary. Errors are exceptions: main() prints one line and
// exits 1; outputs are written only after the mesh exists, so a failed run writes nothing.
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/cli/progress_line.hpp"
#include "ablmg/cli/config.hpp"
#include "ablmg/cli/mesh_output.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/mesher/initial_placement.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <iomanip>
#include <iostream>

namespace ablmg::cli {
namespace {

const char* kHelp =
    R"(usage: ablmg mesh CONFIG.json [-o OUT.{mesh,vtu,png}]... [--bubbles-only] [--report R.json] [--seed N] [--max-nodes N] [-v N]
       ablmg mesh [CONFIG.json] [--seed N] [--max-nodes N] --print-options

Meshes the domain of CONFIG.json with the metric it prescribes (schema: docs/config.md).
  -o PATH          output, format by extension (repeatable; adds to the config's "outputs"):
                   .mesh (medit, + metric .sol beside it), .vtu (VTK), .png (bubbles over mesh)
  --bubbles-only   stop after node placement (paper §3): outputs hold the nodes and bubbles
  --report PATH    JSON report: resolved options, statistics, outputs
  --seed N         overrides options.placement.seed
  --max-nodes N    refuse (before allocating) a metric asking for more than N nodes
                   (options.placement.maxNodes; default 50 000 000)
  -v N             0: no progress line on stderr (shown on a terminal only; default 1)
  --print-options  print the mesher options in effect (JSON: the preset, options.preset of the
                   config or "mesh", and every field) and exit; without CONFIG.json, the defaults
  -h, --help       this text
A mesh of 2e5 triangles or more (from the metric) is built in a second run of the program under
glibc's huge-page heap (GLIBC_TUNABLES; faster where page faults are dear, the same mesh);
GLIBC_TUNABLES set by the user, even empty, keeps one run.
)";

/// Fixed corners closer than the metric asks crowd the boundary (every point of a loop that is
/// not `smooth` is a mesh vertex): a circle given as a 96-gon of side 0.02 under h = 0.1 came
/// out with q min 0.27 and 37 repaired triangles, against 0.80 and none with "smooth": true.
/// Prints one note per such loop (segments of metric length < 0.5 at their midpoint).
void noteCrowdedCorners(const Domain& domain, const MetricField& field) {
  for (std::size_t l = 0; l < domain.loops().size(); ++l) {
    const auto& loop = domain.loops()[l];
    if (loop.smooth) continue;
    int shortSegments = 0;
    try {
      for (std::size_t k = 0; k < loop.points.size(); ++k) {
        const Vec2 &p = loop.points[k], &q = loop.points[(k + 1) % loop.points.size()];
        if (field.at(0.5 * (p + q)).length(q - p) < 0.5) ++shortSegments;
      }
    } catch (const std::exception&) {
      return;  // a bad metric is reported by the mesher itself, with its location
    }
    if (shortSegments > 0)
      std::cerr << "ablmg mesh: note: loop " << l << " has " << shortSegments << " of " << loop.points.size()
                << " segments shorter than half the metric size; all its points are fixed vertices. If the loop"
                   " samples a curve, set \"smooth\": true in the domain (docs/config.md)\n";
  }
}

/// The command line, as parsed. seed, maxNodes < 0: not given (the config's).
struct MeshArgs {
  std::string configPath, reportPath;
  std::vector<std::string> outputs;
  bool help = false, bubblesOnly = false, printOptions = false;
  long long seed = -1, maxNodes = -1;
  int verbosity = 1;
};

MeshArgs parseMeshArgs(const std::vector<std::string>& args) {
  MeshArgs r;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size(), a << " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      r.help = true;
      return r;
    } else if (a == "-o") {
      r.outputs.push_back(value());
      checkOutputPath(r.outputs.back(), "-o");
    } else if (a == "--report") {
      r.reportPath = value();
    } else if (a == "--bubbles-only") {
      r.bubblesOnly = true;
    } else if (a == "--print-options") {
      r.printOptions = true;
    } else if (a == "--seed") {
      r.seed = parseInteger(value(), "mesh: --seed", 0, std::numeric_limits<long long>::max());
    } else if (a == "-v") {
      r.verbosity = int(parseInteger(value(), "mesh: -v", 0, 10));
    } else if (a == "--max-nodes") {
      r.maxNodes = parseInteger(value(), "mesh: --max-nodes", 1, std::numeric_limits<long long>::max());
    } else if (!a.empty() && a[0] == '-') {
      ABLMG_REQUIRE(false, "unknown option '" << a << "' (see ablmg mesh --help)");
    } else {
      ABLMG_REQUIRE(r.configPath.empty(), "more than one config file ('" << r.configPath << "', '" << a << "')");
      r.configPath = a;
    }
  }
  ABLMG_REQUIRE(!r.configPath.empty() || r.printOptions, "missing CONFIG.json (see ablmg mesh --help)");
  return r;
}

/// The mesh (or, with bubblesOnly, the placed nodes alone), the metric at its vertices and the
/// statistics of every stage as JSON.
struct MeshOutcome {
  Mesh2 mesh;
  std::vector<Metric2> metric;
  nlohmann::json stats;
};

MeshOutcome meshOrPlace(const Config& cfg, const std::string& configPath) {
  MeshOutcome o;
  if (cfg.options.placement.bubblesOnly) {
    auto placed = mesher::placeNodes(cfg.domain, *cfg.metric, cfg.options.placement, cfg.options.progress);
    o.mesh.vertices = placed.nodes.positions;
    o.metric = std::move(placed.metrics);
    o.stats = {{"placement", placementStatsJson(placed.stats)}};
  } else {
    auto r = cfg.regions.empty()
                 ? mesher::meshDomain(cfg.domain, *cfg.metric, cfg.options)
                 : adapt::meshDomainWithRegions(cfg.domain, cfg.regions, *cfg.metric, cfg.options, configPath);
    o.mesh = std::move(r.mesh);
    o.metric = std::move(r.metric);
    o.stats = meshStatsJson(r.stats);
  }
  return o;
}

/// A note on stderr when the metric changes by more than its own size within one element along
/// more than kJumpNoteShare of the mesh's sides (mesher::metricJumpShare at ratio 2; meshes of
/// smooth or graded metrics stay ≤ 0.1 %): no mesh gives such a metric unit edges, and the user
/// sees why before measuring the result.
void noteFastVaryingMetric(const MeshOutcome& o, const std::string& configPath) {
  constexpr double kJumpNoteShare = 0.005;
  const double share = mesher::metricJumpShare(o.mesh, o.metric, 2.0);
  if (share <= kJumpNoteShare) return;
  std::cerr << "ablmg mesh: note: on " << std::fixed << std::setprecision(1) << 100 * share
            << " % of the triangles' sides the metric length measured at one end is over twice that at the"
               " other: the metric varies by more than its own size within one element, so no mesh gives it"
               " unit edges there (measure: ablmg stats OUT.mesh --metric "
            << (configPath.empty() ? std::string("CONFIG.json") : configPath)
            << "). Sizes that change by at most a factor of about 1.5 from one element to the next avoid it.\n"
            << std::defaultfloat;
}

/// Every output (atomic each) and the report; on failure removes the ones already written.
void writeMeshOutputs(const Config& cfg, const std::vector<std::string>& outputs, const std::string& reportPath,
                      nlohmann::json report, const MeshOutcome& o, double seconds) {
  std::vector<std::string> written;
  try {
    for (const auto& path : outputs) {
      writeMeshOutput(path, cfg.domain, o.mesh, o.metric);
      written.push_back(path);
    }
    if (!reportPath.empty()) {
      report["stats"] = o.stats;
      report["vertices"] = o.mesh.numVertices();
      report["triangles"] = o.mesh.numTriangles();
      report["seconds"] = seconds;
      io::writeFileAtomically(reportPath, [&](std::ostream& os) { os << report.dump(2) << "\n"; });
    }
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    throw;
  }
}

/// Triangles of a unit mesh of the metric on the domain: (4/√3) ∫ √det M (unit equilateral
/// triangles have area √3/4 in the metric); 0 where the metric cannot be evaluated (the mesher
/// then stops with its own message).
double expectedTriangles(const Config& cfg) {
  try {
    return 4 / std::sqrt(3.0) * mesher::metricArea(cfg.domain, mesher::DomainGeometry(cfg.domain), *cfg.metric, 64);
  } catch (const std::exception&) { return 0; }
}

int runMesh(const std::vector<std::string>& argv) {
  const MeshArgs args = parseMeshArgs(argv);
  if (args.help) {
    std::cout << kHelp;
    return 0;
  }
  // 1. Configuration; the command line overrides it.
  Config cfg;
  if (!args.configPath.empty()) cfg = loadConfig(args.configPath);
  if (args.seed >= 0) cfg.options.placement.seed = std::uint64_t(args.seed);
  if (args.maxNodes > 0) cfg.options.placement.maxNodes = long(args.maxNodes);
  if (args.bubblesOnly) cfg.options.placement.bubblesOnly = true;
  if (args.printOptions) {
    printEffectiveOptions("mesh", cfg.preset, cfg.options, {{"config", args.configPath}});
    return 0;
  }
  std::vector<std::string> outputs = args.outputs;
  for (const auto* o : {&cfg.outputs.mesh, &cfg.outputs.vtu, &cfg.outputs.png})
    if (!o->empty()) outputs.push_back(*o);
  const std::string reportPath = args.reportPath.empty() ? cfg.outputs.report : args.reportPath;
  ABLMG_REQUIRE(!outputs.empty() || !reportPath.empty(),
                "no output (give -o OUT.mesh|.vtu|.png or \"outputs\" in the config)");

  // A large mesh is built in a new run with glibc's huge-page heap (command.hpp), so nothing is
  // printed before that decision.
  rerunWithHugePageHeapIfLarge(expectedTriangles(cfg));

  // 2. Print every option in effect, defaults included.
  const nlohmann::json resolved = {{"config", args.configPath},
                                   {"domain", {{"loops", cfg.domain.loops().size()}, {"area", cfg.domain.area()}}},
                                   {"metric", cfg.metricDescription},
                                   {"options", meshOptionsToJson(cfg.options)},
                                   {"outputs", outputs},
                                   {"report", reportPath}};
  std::cout << "ablmg mesh: options " << resolved.dump() << "\n";

  // 3. Mesh (or place the bubbles).
  noteCrowdedCorners(cfg.domain, *cfg.metric);
  ProgressLine progress("mesh", args.verbosity);
  cfg.options.progress = progress.callback();
  const Stopwatch watch;
  const MeshOutcome o = meshOrPlace(cfg, args.configPath);
  const double seconds = watch.seconds();
  progress.clear();

  // 4. Outputs.
  writeMeshOutputs(cfg, outputs, reportPath, resolved, o, seconds);
  const nlohmann::json& stats = o.stats;
  std::cout << "ablmg mesh: " << o.mesh.numVertices() << " vertices, " << o.mesh.numTriangles() << " triangles in "
            << seconds << " s (" << stats["placement"]["steps"] << " steps, residual "
            << stats["placement"]["finalResidual"];
  if (stats.contains("connect")) std::cout << ", repaired triangles " << stats["connect"]["repairedTriangles"];
  std::cout << ")";
  for (const auto& path : outputs) std::cout << " -> " << path;
  std::cout << "\n";
  noteFastVaryingMetric(o, args.configPath);
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("mesh", "mesh a domain from a JSON config (docs/config.md)", ablmg::cli::runMesh)
