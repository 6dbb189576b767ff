// ablmg remesh -in IN.mesh -sol IN.sol -out OUT.mesh [-hmin H] [-hmax H] [-hgrad G] [-v N] [--report R.json]
//
// The flags and files of MMG's mmg2d_O3, so ablmg drops into loops written for MMG: the input
// mesh gives the domain (its boundary edges, with their refs, become the loops) and, with the
// .sol, the background metric (BackgroundMetricField, log-Euclidean interpolation). Writes
// OUT.mesh and the metric at the new vertices as OUT.sol (as MMG does); without -out,
// IN.o.mesh. Nothing is written if anything fails.
// The remeshing itself is adapt::remesh (adapt/remesh.hpp); this file parses the flags into
// its RemeshOptions, reads the files, calls it, writes the files and prints.
#include "ablmg/adapt/metric_from_hessian.hpp"
#include "ablmg/adapt/remesh.hpp"
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/cli/progress_line.hpp"
#include "ablmg/cli/config.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <iostream>
#include <vector>

namespace ablmg::cli {
namespace {

const char* kHelp =
    R"(usage: ablmg remesh -in IN.mesh [-sol|-met IN.sol] [-out OUT.mesh] [-hmin H] [-hmax H] [-hgrad G] [-v N]

Remeshes IN.mesh so that edges have unit length in the metric of IN.sol (MMG's mmg2d flags).
  -in IN.mesh      input mesh (medit, 2D); its boundary edges and refs define the domain.
                   A file with Edges and no Triangles (a boundary discretization, closed
                   loops) is meshed inside its loops (adapt/boundary_mesh.hpp): the size from
                   the per-vertex SOL or -hsiz, interpolated along and into the domain
  --interior-loops holes|subdomains
                   edges-only input: a loop inside another is a hole (default; one inside a
                   hole an island) or an interface between two subdomains
  -sol, -met SOL   per-vertex metric (type 1 sizes or type 3 tensors m11 m12 m22);
                   default IN.sol
  -hsiz H          constant size H at every vertex (no .sol read), as MMG
  -met-field K     with several solution fields in SOL, use field K (1-based; type 1 or 3);
                   default: the one tensor field if there is exactly one, else the first
  -out OUT.mesh    output mesh (+ OUT.sol, the metric at the new vertices); default IN.o.mesh
  -hmin H, -hmax H clamp the metric sizes h1, h2 to [hmin, hmax]
  -hgrad G         size gradation β > 1 (metric-space, adapt/gradation.hpp), applied on the
                   input mesh after clamping; default 1.3 as MMG; -1 disables
  Node placement stops early on a quality plateau (plateauSteps = 10, plateauGain = 0.01; see
  mesher/place_nodes.hpp): graded metrics rarely let the bubble residual settle.
  -v N             verbosity, an integer in [-1, 10]: -1 silent, 0 summary only, >= 1 options + summary (default 1),
                   >= 2 also the time of every phase (read, gradation, domain, background
                   field, placement, connection, quality post-pass, validation, write);
                   a progress line on stderr if it is a terminal, unless -v is 0 or -1
  --metric-quantum Q  snap the metric to a grid of step Q first (0 = off, the default; e.g.
                   0.00390625 = 2^-8): metrics differing by round-off give the same mesh
                   (adapt/metric_snap.hpp)
  --print-options, -val
                   print the options in effect (JSON: these flags and the mesher's, the
                   "remesh" preset) and exit; -in is then not needed
  -nosurf          keep the boundary and the interfaces as they are: every boundary and
                   interface edge of IN.mesh becomes a required edge (kept as one edge, its
                   vertices kept), so only the inside is remeshed, as MMG's -nosurf
  --seed N         placement seed: 0 (default) the nodes as placed; N > 0 a different mesh of
                   the same statistics, the same for the same N
  --lattice O      orientation of the initial bubble lattice: auto (default: short where
                   h1/h2 >= 16, axes where <= 8), axes, short (one row along each node's
                   short-size direction: lower FE errors for Hessian metrics, see
                   docs/method.md), long
  --warm-start W   auto (default), on, off: seed the placement with the input's interior
                   vertices (auto: when half of its edges are already within 10 % of unit
                   length, e.g. a mesh remeshed to its own metric; see adapt/remesh.hpp)
  --report R.json  JSON report: options, statistics of every stage, times, and the output's
                   quality in its metric (as `ablmg stats OUT.mesh --sol OUT.sol --json`)
  -h, --help       this text
An output of 2e5 triangles or more (from the metric) is built in a second run of the program
under glibc's huge-page heap (GLIBC_TUNABLES; faster where page faults are dear, the same mesh);
GLIBC_TUNABLES set by the user, even empty, keeps one run.
)";

/// readMesh(in), readSol(sol, its vertex count), requireValid(in), with the same errors in the
/// same order, but the .sol is read on a second thread while this one reads and validates the
/// mesh. A failed or mismatched .sol is read again after the mesh, for the sequential message.
/// The reader's warnings (repaired quirks of the file) are returned, once the mesh is known valid.
/// With hsiz > 0 no .sol is read: every vertex gets the size hsiz (MMG's -hsiz).
struct RemeshInputs {
  Mesh2 mesh;
  std::vector<Metric2> metrics;
  std::vector<std::string> warnings;
};
RemeshInputs readInputs(const std::string& in, const std::string& sol, int field, double hsiz) {
  auto solRead = std::async(std::launch::async, [&sol, field, hsiz] {
    return hsiz > 0 ? std::vector<Metric2>() : io::readSol(sol, -1, field);
  });
  Mesh2 mesh;
  std::vector<std::string> warnings;
  bool valid = false;
  try {
    io::MeshFile file = io::readMeshFile(in);
    warnings = std::move(file.warnings);
    mesh = std::move(file.mesh);
    valid = mesh.validate().ok;
  } catch (...) {
    solRead.wait();
    throw;
  }
  std::vector<Metric2> metrics;
  bool solOk = true;
  try {
    metrics = solRead.get();
  } catch (...) { solOk = false; }
  if (hsiz > 0)
    metrics.assign(std::size_t(mesh.numVertices()), Metric2::isotropic(hsiz));
  else if (!solOk || long(metrics.size()) != mesh.numVertices())
    metrics = io::readSol(sol, mesh.numVertices(), field);
  // Edges only: remesh() triangulates them. Errors name the file's own (1-based) ids.
  if (!valid && mesh.numTriangles() > 0) mesh.requireValid(in, std::nullopt, 1e-9, 1);
  return {std::move(mesh), std::move(metrics), std::move(warnings)};
}

/// Triangles of a unit mesh of the input's metric: (4/√3) × its complexity ∫ √det M (two
/// triangles of area √3/4 per vertex); 0 for an input without triangles.
double expectedTriangles(const Mesh2& mesh, std::span<const Metric2> metrics) {
  return mesh.numTriangles() > 0 ? 4 / std::sqrt(3.0) * adapt::metricComplexity(mesh, metrics) : 0;
}

/// The command line, as parsed; paths completed with their defaults.
struct RemeshArgs {
  std::string in, sol, out, outSol, reportPath;
  double hmin = 0, hmax = std::numeric_limits<double>::infinity(), hgrad = 1.3, hsiz = 0, metricQuantum = 0;
  adapt::InteriorLoops interiorLoops = adapt::InteriorLoops::Holes;
  int verbose = 1, metField = 0;
  bool help = false, printOptions = false, noSurf = false;
  long long seed = 0;
  mesher::LatticeOrientation lattice = mesher::LatticeOrientation::Auto;
  adapt::RemeshOptions::WarmStart warmStart = adapt::RemeshOptions::WarmStart::IfFits;
};

/// Parses the flags; errors name the flag. Stops at -h (help = true).
RemeshArgs parseRemeshArgs(const std::vector<std::string>& args) {
  RemeshArgs r;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size(), a << " needs a value");
      return args[++i];
    };
    const auto number = [&] { return parseNumber(value(), "remesh: " + a); };
    if (a == "-h" || a == "--help" || a == "-help") {
      r.help = true;
      return r;
    } else if (a == "-in")
      r.in = value();
    else if (a == "-sol" || a == "-met")
      r.sol = value();
    else if (a == "-out")
      r.out = value();
    else if (a == "-met-field")
      r.metField = int(parseInteger(value(), "remesh: " + a, 1, 64));
    else if (a == "-hmin")
      r.hmin = number();
    else if (a == "-hsiz") {
      r.hsiz = number();
      ABLMG_REQUIRE(r.hsiz > 0, "remesh: -hsiz must be > 0, got " << r.hsiz);
    } else if (a == "-hmax")
      r.hmax = number();
    else if (a == "-hgrad")
      r.hgrad = number();
    else if (a == "-v")
      r.verbose = int(parseInteger(value(), "remesh: " + a, -1, 10));
    else if (a == "--seed")
      r.seed = parseInteger(value(), "remesh: " + a, 0, std::numeric_limits<long long>::max());
    else if (a == "--lattice")
      r.lattice = mesher::parseLatticeOrientation(value());
    else if (a == "--warm-start") {
      const std::string& w = value();
      ABLMG_REQUIRE(w == "auto" || w == "on" || w == "off",
                    "--warm-start: expected auto, on or off, got '" << w << "'");
      r.warmStart = w == "on"    ? adapt::RemeshOptions::WarmStart::On
                    : w == "off" ? adapt::RemeshOptions::WarmStart::Off
                                 : adapt::RemeshOptions::WarmStart::IfFits;
    } else if (a == "--report")
      r.reportPath = value();
    else if (a == "--print-options" || a == "-val")
      r.printOptions = true;
    else if (a == "-nosurf")
      r.noSurf = true;
    else if (a == "--interior-loops") {
      const std::string v = value();
      ABLMG_REQUIRE(v == "holes" || v == "subdomains",
                    "remesh: --interior-loops must be holes or subdomains, got '" << v << "'");
      r.interiorLoops = v == "holes" ? adapt::InteriorLoops::Holes : adapt::InteriorLoops::Subdomains;
    } else if (a == "--metric-quantum") {
      r.metricQuantum = number();
      ABLMG_REQUIRE(r.metricQuantum >= 0, "remesh: --metric-quantum must be >= 0 (0 = off), got " << r.metricQuantum);
    } else if (!a.empty() && a[0] == '-')
      ABLMG_REQUIRE(false, "unknown option '" << a << "' (see ablmg remesh --help)");
    else {
      ABLMG_REQUIRE(r.in.empty(), "more than one input mesh ('" << r.in << "', '" << a << "')");
      r.in = a;  // mmg2d also takes the input as a positional argument
    }
  }
  ABLMG_REQUIRE(!r.in.empty() || r.printOptions, "missing -in IN.mesh (see ablmg remesh --help)");
  ABLMG_REQUIRE(r.hmin >= 0 && r.hmin < r.hmax, "need 0 <= hmin < hmax, got hmin " << r.hmin << ", hmax " << r.hmax);
  const std::filesystem::path inPath(r.in);
  if (r.sol.empty() && !r.in.empty()) r.sol = std::filesystem::path(r.in).replace_extension(".sol").string();
  if (r.out.empty() && !r.in.empty()) r.out = (inPath.parent_path() / (inPath.stem().string() + ".o.mesh")).string();
  ABLMG_REQUIRE(r.printOptions || std::filesystem::path(r.out).extension() == ".mesh",
                "-out '" << r.out << "' must end in .mesh");
  r.outSol = r.out.empty() ? "" : std::filesystem::path(r.out).replace_extension(".sol").string();
  ABLMG_REQUIRE(r.reportPath.empty() || (r.reportPath != r.out && r.reportPath != r.outSol),
                "--report must not be the output mesh or .sol");
  return r;
}

adapt::RemeshOptions remeshOptions(const RemeshArgs& a) {
  adapt::RemeshOptions options;  // plateau stop: see RemeshOptions::mesh and docs/method.md
  options.interiorLoops = a.interiorLoops;
  options.hmin = a.hmin;
  options.hmax = a.hmax;
  options.hgrad = a.hgrad;  // -1 (any value < 0) is "off" for both
  options.name = a.in;
  options.mesh.placement.seed = std::uint64_t(a.seed);
  options.mesh.placement.lattice.orientation = a.lattice;
  options.warmStart = a.warmStart;
  options.metricQuantum = a.metricQuantum;
  return options;
}

/// The options in effect, as printed by -v 1 and --print-options and written to the report.
nlohmann::json resolvedJson(const RemeshArgs& a, const adapt::RemeshOptions& options) {
  using WarmStart = adapt::RemeshOptions::WarmStart;
  return {{"in", a.in},
          {"sol", a.sol},
          {"out", a.out},
          {"outSol", a.outSol},
          {"hmin", a.hmin},
          {"hmax", std::isfinite(a.hmax) ? nlohmann::json(a.hmax) : nlohmann::json("inf")},
          {"hgrad", a.hgrad < 0 ? nlohmann::json("off") : nlohmann::json(a.hgrad)},
          {"v", a.verbose},
          {"warmStart", a.warmStart == WarmStart::On    ? "on"
                        : a.warmStart == WarmStart::Off ? "off"
                                                        : "auto"},
          {"metField", a.metField},
          {"hsiz", a.hsiz},
          {"metricQuantum", a.metricQuantum},
          {"interiorLoops", options.interiorLoops == adapt::InteriorLoops::Holes ? "holes" : "subdomains"},
          {"options", meshOptionsToJson(options.mesh)},
          {"nosurf", a.noSurf},
          {"report", a.reportPath}};
}

/// Seconds of every stage, as the report and -v 2 give them.
struct RemeshTimes {
  double read = 0, write = 0;
};

void writeReport(const std::string& path, nlohmann::json report, const adapt::RemeshResult& r, int inVertices,
                 const RemeshTimes& t) {
  report["stats"] = meshStatsJson(r.stats);
  report["stats"]["clampedMetrics"] = r.clampedMetrics;
  report["stats"]["gradedMetrics"] = r.gradation.corrections;
  report["stats"]["warmStarted"] = r.warmStarted;
  report["stats"]["inputWithin10"] = r.inputWithin10;
  const char* tunables = std::getenv("GLIBC_TUNABLES");  // the heap it ran with (command.hpp)
  report["glibcTunables"] = tunables ? nlohmann::json(tunables) : nlohmann::json(nullptr);
  report["inVertices"] = inVertices;
  report["vertices"] = r.mesh.numVertices();
  report["triangles"] = r.mesh.numTriangles();
  report["seconds"] = {{"read", t.read + r.secondsClamp}, {"gradation", r.secondsGradation},
                       {"domain", r.secondsDomain},       {"backgroundField", r.secondsBackgroundField},
                       {"meshing", r.secondsMeshing},     {"write", t.write}};
  report["quality"] = cli::qualityJson(mesher::meshQuality(r.mesh, r.metric));
  io::writeFileAtomically(path, [&](std::ostream& os) { os << report.dump(2) << "\n"; });
}

void printStageTimes(const adapt::RemeshResult& r, const RemeshTimes& t) {
  const auto& p = r.stats.placement;
  const auto& c = r.stats.connect;
  const auto& q = r.stats.improve;
  std::cout << "ablmg remesh: seconds: read " << t.read + r.secondsClamp << ", gradation " << r.secondsGradation
            << ", domain " << r.secondsDomain << ", background field " << r.secondsBackgroundField << ", placement "
            << p.secondsInitial + p.secondsDynamics + p.secondsAdjacency + p.secondsPopulation << " (initial "
            << p.secondsInitial << ", dynamics " << p.secondsDynamics << " in " << p.steps << " steps"
            << (p.stalled ? " (stalled)" : "") << (p.qualityPlateau ? " (quality plateau)" : "") << ", adjacency "
            << p.secondsAdjacency << ", population " << p.secondsPopulation << "), connection "
            << c.secondsLocalMeshes + c.secondsRepair << ", quality post-pass " << q.seconds << " (q min "
            << q.qMinBefore << " -> " << q.qMinAfter << ", " << q.swaps << " swaps, " << q.moves << " moves, "
            << q.collapses << " collapses), validation " << r.stats.secondsValidate << ", write " << t.write << "\n";
  std::cout << "ablmg remesh: " << (r.warmStarted ? "warm start" : "cold start (lattice)")
            << ", input edges within 10 %: " << r.inputWithin10 << "\n";
}

int runRemesh(const std::vector<std::string>& argv) {
  const RemeshArgs args = parseRemeshArgs(argv);
  if (args.help) {
    std::cout << kHelp;
    return 0;
  }
  adapt::RemeshOptions options = remeshOptions(args);
  const nlohmann::json resolved = resolvedJson(args, options);
  if (args.printOptions) {
    nlohmann::json own = resolved;
    own.erase("options");
    printEffectiveOptions("remesh", "remesh", options.mesh, own);
    return 0;
  }
  ABLMG_REQUIRE(args.hgrad < 0 || args.hgrad > 1, "-hgrad must be > 1 (or -1 to disable), got " << args.hgrad);

  // 1. Input mesh and metric (errors name file:line); the mesh is validated as it is read.
  // A large output is built in a new run with glibc's huge-page heap (command.hpp), so nothing
  // is printed before that decision.
  ProgressLine progress("remesh", args.verbose == -1 ? 0 : args.verbose);
  options.mesh.progress = progress.callback();
  progress.update({.stage = "read"});
  RemeshTimes times;
  Stopwatch watch;
  RemeshInputs inputs = readInputs(args.in, args.sol, args.metField, args.hsiz);
  times.read = watch.seconds();
  progress.clear();
  rerunWithHugePageHeapIfLarge(expectedTriangles(inputs.mesh, inputs.metrics));
  if (args.verbose >= 1) std::cout << "ablmg remesh: options " << resolved.dump() << "\n";
  if (args.verbose >= 0)  // only for inputs that are used: an error stays the one line printed
    for (const auto& w : inputs.warnings) std::cerr << "ablmg remesh: warning: " << w << "\n";
  const int inVertices = inputs.mesh.numVertices();
  if (args.noSurf) adapt::requireBoundaryEdges(inputs.mesh);
  // 2. Clamp, gradation, domain from the boundary, background field, meshing.
  options.inputCheck = BackgroundMetricField::MeshCheck::AlreadyValidated;
  const adapt::RemeshResult r = adapt::remesh(std::move(inputs.mesh), std::move(inputs.metrics), options);
  // 3. Outputs: the mesh and the metric at its vertices (removed again if the second fails).
  progress.update({.stage = "write", .nodes = r.mesh.numVertices()});
  watch.restart();
  io::writeMeshAndSol(args.out, r.mesh, args.outSol, r.metric);
  progress.clear();
  times.write = watch.seconds();
  if (!args.reportPath.empty()) {
    try {
      writeReport(args.reportPath, resolved, r, inVertices, times);
    } catch (...) {
      std::remove(args.out.c_str());  // all or nothing
      std::remove(args.outSol.c_str());
      throw;
    }
  }
  if (args.verbose >= 2) printStageTimes(r, times);
  if (args.verbose >= 0)
    std::cout << "ablmg remesh: " << inVertices << " -> " << r.mesh.numVertices() << " vertices, "
              << r.mesh.numTriangles() << " triangles in " << r.secondsMeshing << " s (" << r.clampedMetrics
              << " metrics clamped, " << r.gradation.corrections << " graded, " << r.stats.connect.repairedTriangles
              << " repaired triangles) -> " << args.out << ", " << args.outSol << "\n";
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("remesh", "remesh IN.mesh to the metric of IN.sol (mmg2d flags)", ablmg::cli::runRemesh)
