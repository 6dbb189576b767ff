// ablmg remesh -in IN.mesh -sol IN.sol -out OUT.mesh [-hmin H] [-hmax H] [-hgrad G] [-v N]
//
// The flags and files of MMG's mmg2d_O3, so ablmg drops into loops written for MMG: the input
// mesh gives the domain (its boundary edges, with their refs, become the loops) and, with the
// .sol, the background metric (BackgroundMetricField, log-Euclidean interpolation). Writes
// OUT.mesh and the metric at the new vertices as OUT.sol (as MMG does); without -out,
// IN.o.mesh. Nothing is written if anything fails.
#include "adapt/gradation.hpp"
#include "cli/command.hpp"
#include "cli/config.hpp"
#include "core/error.hpp"
#include "io/medit.hpp"
#include "mesher/mesher.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <array>
#include <climits>
#include <tuple>
#include <vector>

namespace ablmg::cli {
namespace {

const char* kHelp = R"(usage: ablmg remesh -in IN.mesh [-sol|-met IN.sol] [-out OUT.mesh] [-hmin H] [-hmax H] [-hgrad G] [-v N]

Remeshes IN.mesh so that edges have unit length in the metric of IN.sol (MMG's mmg2d flags).
  -in IN.mesh      input mesh (medit, 2D); its boundary edges and refs define the domain
  -sol, -met SOL   per-vertex metric (type 1 sizes or type 3 tensors m11 m12 m22);
                   default IN.sol
  -out OUT.mesh    output mesh (+ OUT.sol, the metric at the new vertices); default IN.o.mesh
  -hmin H, -hmax H clamp the metric sizes h1, h2 to [hmin, hmax]
  -hgrad G         size gradation β > 1 (metric-space, adapt/gradation.hpp), applied on the
                   input mesh after clamping; default 1.3 as MMG; -1 disables
  Node placement stops early on a quality plateau (plateauSteps = 10, plateauGain = 0.01; see
  mesher/place_nodes.hpp): graded metrics rarely let the bubble residual settle.
  -v N             verbosity: -1 silent, 0 summary only, >= 1 options + summary (default 1),
                   >= 2 also the time of every phase (read, gradation, placement, connection, write)
  --seed N         placement seed (default 1)
  -h, --help       this text
)";

double parseNumber(const std::string& flag, const std::string& v) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(v, &used);
  } catch (...) {
    used = 0;
  }
  ABLMG_REQUIRE(used == v.size() && std::isfinite(x), flag << ": expected a number, got '" << v << "'");
  return x;
}

/// The input mesh's boundary (edges in exactly one triangle, oriented with the mesh on the
/// left) chained into loops; refs from the file's Edges (1 where an edge has none). The loop
/// of largest area is the outer one. Loops are `smooth` so the mesher places its own boundary
/// nodes and keeps only corners (ref changes, turns > 30°).
Domain domainFromBoundary(const Mesh2& mesh, const std::string& name) {
  // Boundary edges: undirected edges of exactly one triangle (sorted (lo, hi, a, b) records).
  struct DirectedEdge {
    int lo, hi, a, b;
    bool operator<(const DirectedEdge& o) const { return std::tie(lo, hi, a, b) < std::tie(o.lo, o.hi, o.a, o.b); }
  };
  std::vector<DirectedEdge> all;
  all.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      all.push_back({std::min(a, b), std::max(a, b), a, b});
    }
  std::sort(all.begin(), all.end());
  std::vector<std::array<int, 3>> refs;  // (lo, hi, ref) of the file's Edges, sorted; the first ref wins
  for (const auto& e : mesh.boundaryEdges) refs.push_back({std::min(e.a, e.b), std::max(e.a, e.b), e.ref});
  std::stable_sort(refs.begin(), refs.end(), [](const auto& x, const auto& y) { return x[0] != y[0] ? x[0] < y[0] : x[1] < y[1]; });
  const int nv = mesh.numVertices();
  std::vector<int> next(static_cast<std::size_t>(nv), -1), nextRef(static_cast<std::size_t>(nv), 1);  // a → b, ref
  bool any = false;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].lo == all[i].lo && all[j].hi == all[i].hi) ++j;
    if (j - i == 1) {
      const int a = all[i].a, b = all[i].b;
      const auto it = std::lower_bound(refs.begin(), refs.end(), std::array<int, 3>{all[i].lo, all[i].hi, INT_MIN},
                                       [](const auto& x, const auto& y) { return x[0] != y[0] ? x[0] < y[0] : x[1] < y[1]; });
      ABLMG_REQUIRE(next[std::size_t(a)] < 0, name << ": boundary vertex " << a + 1 << " starts two boundary edges (non-manifold boundary)");
      next[std::size_t(a)] = b;
      nextRef[std::size_t(a)] = it != refs.end() && (*it)[0] == all[i].lo && (*it)[1] == all[i].hi ? (*it)[2] : 1;
      any = true;
    }
    i = j;
  }
  ABLMG_REQUIRE(any, name << ": mesh has no boundary edges");
  std::vector<BoundaryLoop> loops;
  std::vector<double> areas;
  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  for (int start = 0; start < nv; ++start) {  // loops start at their smallest unused vertex
    if (next[std::size_t(start)] < 0 || used[std::size_t(start)]) continue;
    BoundaryLoop loop;
    loop.smooth = true;
    double area = 0;
    int v = start;
    do {
      used[std::size_t(v)] = 1;
      ABLMG_REQUIRE(next[std::size_t(v)] >= 0, name << ": boundary is not closed at vertex " << v + 1);
      loop.points.push_back(mesh.vertices[v]);
      loop.tags.push_back(nextRef[std::size_t(v)]);
      area += 0.5 * cross(mesh.vertices[v], mesh.vertices[next[std::size_t(v)]]);
      v = next[std::size_t(v)];
      ABLMG_REQUIRE(v == start || !used[std::size_t(v)], name << ": boundary loops touch at vertex " << v + 1);
    } while (v != start);
    loops.push_back(std::move(loop));
    areas.push_back(area);
  }
  const std::size_t outer = std::max_element(areas.begin(), areas.end()) - areas.begin();
  BoundaryLoop o = std::move(loops[outer]);
  loops.erase(loops.begin() + long(outer));
  try {
    return Domain(std::move(o), std::move(loops));
  } catch (const InputError& e) {
    throw InputError(name + ": boundary: " + e.what());
  }
}

int runRemesh(const std::vector<std::string>& args) {
  std::string in, sol, out;
  double hmin = 0, hmax = std::numeric_limits<double>::infinity(), hgrad = 1.3;
  int verbose = 1;
  long long seed = 1;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size(), a << " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help" || a == "-help") {
      std::cout << kHelp;
      return 0;
    } else if (a == "-in") in = value();
    else if (a == "-sol" || a == "-met") sol = value();
    else if (a == "-out") out = value();
    else if (a == "-hmin") hmin = parseNumber(a, value());
    else if (a == "-hmax") hmax = parseNumber(a, value());
    else if (a == "-hgrad") hgrad = parseNumber(a, value());
    else if (a == "-v") verbose = int(parseNumber(a, value()));
    else if (a == "--seed") seed = (long long)parseNumber(a, value());
    else if (!a.empty() && a[0] == '-') ABLMG_REQUIRE(false, "unknown option '" << a << "' (see ablmg remesh --help)");
    else {
      ABLMG_REQUIRE(in.empty(), "more than one input mesh ('" << in << "', '" << a << "')");
      in = a;  // mmg2d also takes the input as a positional argument
    }
  }
  ABLMG_REQUIRE(!in.empty(), "missing -in IN.mesh (see ablmg remesh --help)");
  ABLMG_REQUIRE(hmin >= 0 && hmin < hmax, "need 0 <= hmin < hmax, got hmin " << hmin << ", hmax " << hmax);
  ABLMG_REQUIRE(seed >= 0, "--seed must be >= 0");
  const std::filesystem::path inPath(in);
  if (sol.empty()) sol = std::filesystem::path(in).replace_extension(".sol").string();
  if (out.empty()) out = (inPath.parent_path() / (inPath.stem().string() + ".o.mesh")).string();
  ABLMG_REQUIRE(std::filesystem::path(out).extension() == ".mesh", "-out '" << out << "' must end in .mesh");
  const std::string outSol = std::filesystem::path(out).replace_extension(".sol").string();

  mesher::MeshOptions options;
  // Early stop on a quality plateau (place_nodes.hpp): < 1 point of ±10 % pairs gained in 10
  // steps. MMG users remesh every cycle; README "Speed" has the time against quality table.
  options.placement.plateauSteps = 10;
  options.placement.plateauGain = 0.01;
  options.placement.seed = std::uint64_t(seed);
  if (verbose >= 1) {
    const nlohmann::json resolved = {{"in", in}, {"sol", sol}, {"out", out}, {"outSol", outSol}, {"hmin", hmin},
                                     {"hmax", std::isfinite(hmax) ? nlohmann::json(hmax) : nlohmann::json("inf")},
                                     {"hgrad", hgrad < 0 ? nlohmann::json("off") : nlohmann::json(hgrad)}, {"v", verbose},
                                     {"options", meshOptionsToJson(options)}};
    std::cout << "ablmg remesh: options " << resolved.dump() << "\n";
  }
  ABLMG_REQUIRE(hgrad < 0 || hgrad > 1, "-hgrad must be > 1 (or -1 to disable), got " << hgrad);

  using Clock = std::chrono::steady_clock;
  const auto tRead = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  // 1. Input mesh and metric (errors name file:line).
  Mesh2 mesh = io::readMesh(in);
  std::vector<Metric2> metrics = io::readSol(sol, mesh.numVertices());
  mesh.requireValid(in);
  // 2. Clamp sizes to [hmin, hmax].
  long clamped = 0;
  for (auto& m : metrics) {
    const auto e = m.eigen();
    const double h1 = std::clamp(e.h1, std::max(hmin, 1e-300), hmax), h2 = std::clamp(e.h2, std::max(hmin, 1e-300), hmax);
    if (h1 != e.h1 || h2 != e.h2) {
      m = Metric2::fromSizes(h1, h2, e.theta);
      ++clamped;
    }
  }
  const double secondsRead = since(tRead);
  // 3. Gradation (sizes grow by at most ≈ hgrad per unit metric length along the input edges).
  const auto tGrad = Clock::now();
  adapt::GradationStats grad;
  if (hgrad > 1) grad = adapt::limitGradation(mesh, metrics, {.hgrad = hgrad});
  // 4. Domain from the boundary; the input mesh + metric are the background field.
  const double secondsGradation = since(tGrad);
  const Domain domain = domainFromBoundary(mesh, in);
  const int inVertices = mesh.numVertices();
  const BackgroundMetricField field(std::move(mesh), std::move(metrics));
  const auto t0 = std::chrono::steady_clock::now();
  auto r = mesher::meshDomain(domain, field, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // 5. Outputs: the mesh and the metric at its vertices (removed again if the second fails).
  const auto tWrite = Clock::now();
  io::writeMesh(out, r.mesh);
  try {
    io::writeSol(outSol, r.metric);
  } catch (...) {
    std::remove(out.c_str());
    throw;
  }
  const double secondsWrite = since(tWrite);
  if (verbose >= 2) {
    const auto& p = r.stats.placement;
    const auto& c = r.stats.connect;
    std::cout << "ablmg remesh: seconds: read " << secondsRead << ", gradation " << secondsGradation << ", placement "
              << p.secondsInitial + p.secondsDynamics + p.secondsAdjacency + p.secondsPopulation << " (initial "
              << p.secondsInitial << ", dynamics " << p.secondsDynamics << " in " << p.steps << " steps"
              << (p.stalled ? " (stalled)" : "") << (p.qualityPlateau ? " (quality plateau)" : "") << ", adjacency " << p.secondsAdjacency << ", population "
              << p.secondsPopulation << "), connection " << c.secondsLocalMeshes + c.secondsRepair << ", validation "
              << r.stats.secondsValidate << ", write " << secondsWrite << "\n";
  }
  if (verbose >= 0)
    std::cout << "ablmg remesh: " << inVertices << " -> " << r.mesh.numVertices() << " vertices, " << r.mesh.numTriangles()
              << " triangles in " << seconds << " s (" << clamped << " metrics clamped, " << grad.corrections << " graded) -> " << out << ", " << outSol << "\n";
  return 0;
}

} // namespace
} // namespace ablmg::cli

ABLMG_COMMAND("remesh", "remesh IN.mesh to the metric of IN.sol (mmg2d flags)", ablmg::cli::runRemesh)
