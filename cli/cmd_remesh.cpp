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
#include <cstdint>
#include <filesystem>
#include <future>
#include <iostream>
#include <unordered_map>
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
                   >= 2 also the time of every phase (read, gradation, domain, background
                   field, placement, connection, quality post-pass, validation, write)
  --seed N         placement seed (default 1)
  --lattice O      orientation of the initial bubble lattice: axes (default), short (one row
                   along each node's short-size direction: lower FE errors for Hessian
                   metrics, see README), long
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

/// The boundary as a successor map: next[a] = b for each boundary edge a→b (−1 elsewhere),
/// nextRef[a] = its ref.
struct BoundaryChain {
  std::vector<int> next, nextRef;
};

/// The edges in exactly one triangle, oriented as in it, in triangle order, with the refs of
/// the file's Edges (a repeated edge takes its last ref; 1 where there is none). Undirected
/// edges are grouped by their smaller vertex (counting sort, O(n), no std::map).
BoundaryChain chainByCounting(const Mesh2& mesh, const std::string& name) {
  const int nv = mesh.numVertices();
  const auto sz = [](int i) { return static_cast<std::size_t>(i); };
  std::vector<int> rowStart(sz(nv) + 1, 0), his(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++rowStart[sz(std::min(t[k], t[(k + 1) % 3])) + 1];
  for (int v = 0; v < nv; ++v) rowStart[sz(v) + 1] += rowStart[sz(v)];
  {
    std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) his[sz(fill[sz(std::min(t[k], t[(k + 1) % 3]))]++)] = std::max(t[k], t[(k + 1) % 3]);
  }
  const auto trianglesOf = [&](int lo, int hi) {  // number of triangles with the edge {lo, hi}
    return std::count(his.begin() + rowStart[sz(lo)], his.begin() + rowStart[sz(lo) + 1], hi);
  };
  std::unordered_map<std::uint64_t, int> refs;
  refs.reserve(mesh.boundaryEdges.size());
  const auto key = [](int lo, int hi) { return std::uint64_t(std::uint32_t(lo)) << 32 | std::uint32_t(hi); };
  for (const auto& e : mesh.boundaryEdges) refs[key(std::min(e.a, e.b), std::max(e.a, e.b))] = e.ref;
  BoundaryChain c{std::vector<int>(sz(nv), -1), std::vector<int>(sz(nv), 1)};
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (trianglesOf(std::min(a, b), std::max(a, b)) != 1) continue;
      ABLMG_REQUIRE(c.next[sz(a)] < 0, name << ": boundary vertex " << a + 1 << " starts two boundary edges (non-manifold boundary)");
      const auto it = refs.find(key(std::min(a, b), std::max(a, b)));
      c.next[sz(a)] = b;
      c.nextRef[sz(a)] = it == refs.end() ? 1 : it->second;
    }
  return c;
}

/// The input mesh's boundary (edges in exactly one triangle, oriented with the mesh on the
/// left) chained into loops; refs from the file's Edges (1 where an edge has none). The loop
/// of largest area is the outer one. Loops are `smooth` so the mesher places its own boundary
/// nodes and keeps only corners (ref changes, turns > 30°). Loops start at their smallest
/// vertex, in that order (deterministic output).
/// `mesh` must be valid (Mesh2::validate): then its edges in exactly one triangle are the
/// file's Edges, listed once and oriented as in their triangle (validate checks all three),
/// and the chain comes straight from them. A vertex starting two of them (boundary loops
/// that touch) sends it through chainByCounting, for the same message as before.
Domain domainFromBoundary(const Mesh2& mesh, const std::string& name) {
  const int nv = mesh.numVertices();
  const auto sz = [](int i) { return static_cast<std::size_t>(i); };
  BoundaryChain chain{std::vector<int>(sz(nv), -1), std::vector<int>(sz(nv), 1)};
  bool any = false, pinched = false;
  for (const auto& e : mesh.boundaryEdges) {
    pinched = pinched || chain.next[sz(e.a)] >= 0;
    chain.next[sz(e.a)] = e.b;
    chain.nextRef[sz(e.a)] = e.ref;
    any = true;
  }
  if (pinched || !any) {
    chain = chainByCounting(mesh, name);
    any = std::any_of(chain.next.begin(), chain.next.end(), [](int b) { return b >= 0; });
  }
  const auto& next = chain.next;
  const auto& nextRef = chain.nextRef;
  ABLMG_REQUIRE(any, name << ": mesh has no boundary edges");
  std::vector<BoundaryLoop> loops;
  std::vector<double> areas;
  std::vector<char> used(sz(nv), 0);
  for (int start = 0; start < nv; ++start) {  // loops start at their smallest vertex, in that order
    if (next[sz(start)] < 0 || used[sz(start)]) continue;
    BoundaryLoop loop;
    loop.smooth = true;
    double area = 0;
    int v = start;
    do {
      used[sz(v)] = 1;
      ABLMG_REQUIRE(next[sz(v)] >= 0, name << ": boundary is not closed at vertex " << v + 1);
      loop.points.push_back(mesh.vertices[v]);
      loop.tags.push_back(nextRef[sz(v)]);
      area += 0.5 * cross(mesh.vertices[v], mesh.vertices[next[sz(v)]]);
      v = next[sz(v)];
      ABLMG_REQUIRE(v == start || !used[sz(v)], name << ": boundary loops touch at vertex " << v + 1);
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

/// readMesh(in), readSol(sol, its vertex count), requireValid(in), with the same errors in the
/// same order, but the .sol is read on a second thread while this one reads and validates the
/// mesh. A failed or mismatched .sol is read again after the mesh, for the sequential message.
std::pair<Mesh2, std::vector<Metric2>> readInputs(const std::string& in, const std::string& sol) {
  auto solRead = std::async(std::launch::async, [&sol] { return io::readSol(sol); });
  Mesh2 mesh;
  bool valid = false;
  try {
    mesh = io::readMesh(in);
    valid = mesh.validate().ok;
  } catch (...) {
    solRead.wait();
    throw;
  }
  std::vector<Metric2> metrics;
  bool solOk = true;
  try {
    metrics = solRead.get();
  } catch (...) {
    solOk = false;
  }
  if (!solOk || long(metrics.size()) != mesh.numVertices()) metrics = io::readSol(sol, mesh.numVertices());
  if (!valid) mesh.requireValid(in);
  return {std::move(mesh), std::move(metrics)};
}

int runRemesh(const std::vector<std::string>& args) {
  std::string in, sol, out;
  double hmin = 0, hmax = std::numeric_limits<double>::infinity(), hgrad = 1.3;
  int verbose = 1;
  long long seed = 1;
  mesher::LatticeOrientation lattice = mesher::LatticeOrientation::Axes;
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
    else if (a == "--lattice") lattice = mesher::parseLatticeOrientation(value());
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
  options.placement.lattice.orientation = lattice;
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
  auto [mesh, metrics] = readInputs(in, sol);
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
  const auto tDomain = Clock::now();
  const Domain domain = domainFromBoundary(mesh, in);
  const double secondsDomain = since(tDomain);
  const int inVertices = mesh.numVertices();
  const auto tField = Clock::now();
  // readInputs validated the mesh; the clamping, gradation and domain do not change it.
  const BackgroundMetricField field(std::move(mesh), std::move(metrics), BackgroundMetricField::MeshCheck::AlreadyValidated);
  const double secondsField = since(tField);
  const auto t0 = std::chrono::steady_clock::now();
  auto r = mesher::meshDomain(domain, field, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // 5. Outputs: the mesh and the metric at its vertices (removed again if the second fails).
  const auto tWrite = Clock::now();
  io::writeMeshAndSol(out, r.mesh, outSol, r.metric);
  const double secondsWrite = since(tWrite);
  if (verbose >= 2) {
    const auto& p = r.stats.placement;
    const auto& c = r.stats.connect;
    std::cout << "ablmg remesh: seconds: read " << secondsRead << ", gradation " << secondsGradation << ", domain " << secondsDomain
              << ", background field " << secondsField << ", placement "
              << p.secondsInitial + p.secondsDynamics + p.secondsAdjacency + p.secondsPopulation << " (initial "
              << p.secondsInitial << ", dynamics " << p.secondsDynamics << " in " << p.steps << " steps"
              << (p.stalled ? " (stalled)" : "") << (p.qualityPlateau ? " (quality plateau)" : "") << ", adjacency " << p.secondsAdjacency << ", population "
              << p.secondsPopulation << "), connection " << c.secondsLocalMeshes + c.secondsRepair << ", quality post-pass "
              << r.stats.improve.seconds << " (q min " << r.stats.improve.qMinBefore << " -> " << r.stats.improve.qMinAfter << ", "
              << r.stats.improve.swaps << " swaps, " << r.stats.improve.moves << " moves, " << r.stats.improve.collapses
              << " collapses), validation " << r.stats.secondsValidate
              << ", write " << secondsWrite << "\n";
  }
  if (verbose >= 0)
    std::cout << "ablmg remesh: " << inVertices << " -> " << r.mesh.numVertices() << " vertices, " << r.mesh.numTriangles()
              << " triangles in " << seconds << " s (" << clamped << " metrics clamped, " << grad.corrections << " graded) -> " << out << ", " << outSol << "\n";
  return 0;
}

} // namespace
} // namespace ablmg::cli

ABLMG_COMMAND("remesh", "remesh IN.mesh to the metric of IN.sol (mmg2d flags)", ablmg::cli::runRemesh)
