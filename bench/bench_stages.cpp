// Benchmark suite (scripts/bench.sh): every stage of the pipeline at one size, and the table.
//
//   bench_stages --triangles N --json OUT.json   one size, one process (so that the peak memory
//                                                 is this size's): mesh, write, P1 solve
//   bench_stages --table A.json B.json ... [--md OUT.md] [--json OUT.json]
//                                                 the sizes side by side, with fitted exponents
//
// The case is the one of docs/benchmarks.md's stage table: the radius-10 disk with the constant
// anisotropic metric h1 = 2.5 h2, θ = π/4, sized so that the mesh has about N triangles.
// Stages: initial placement, dynamics (and per step), adjacency upkeep, population control,
// ABLMG connection, validation (mesher::MeshResult stats), .mesh and .vtu writing, P1 assembly
// and CHOLMOD solve of a manufactured problem on the mesh (fem "smooth"). The growth exponent
// of a stage is the least-squares slope of log(time) against log(triangles) over the sizes,
// and also between the two largest. scripts/bench.sh runs the whole suite.
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/test_problems.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/mesher.hpp"

#include <nlohmann/json.hpp>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace ablmg;

namespace {

int fail(const std::string& msg) {
  std::cerr << "bench_stages: " << msg << "\n"
            << "usage: bench_stages --triangles N --json OUT.json | --table A.json B.json ... [--md OUT.md] [--json "
               "OUT.json]\n";
  return 2;
}

nlohmann::json runSize(double triangles) {
  // N nodes ≈ T/2; a unit equilateral triangulation has (2/√3)·A/(h1 h2) nodes.
  const double h1h2 = 2.0 / std::sqrt(3.0) * std::numbers::pi * 100.0 / (0.5 * triangles);
  const double h2 = std::sqrt(h1h2 / 2.5), h1 = 2.5 * h2;
  const Domain disk = Domain::disk({0, 0}, 10);
  const ConstantMetricField metric(Metric2::fromSizes(h1, h2, std::numbers::pi / 4));

  Stopwatch watch;
  const mesher::MeshResult r = mesher::meshDomain(disk, metric);
  const double whole = watch.seconds();
  const auto& p = r.stats.placement;
  const auto& c = r.stats.connect;

  const std::string dir = std::filesystem::temp_directory_path() / ("bench_stages_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  watch.restart();
  io::writeMesh(dir + "/m.mesh", r.mesh);
  const double writeMesh = watch.seconds();
  watch.restart();
  io::writeVtu(dir + "/m.vtu", r.mesh);
  const double writeVtu = watch.seconds();
  std::filesystem::remove_all(dir);

  const fem::PoissonSolution s = fem::solvePoisson(r.mesh, fem::makeProblem("smooth").poisson());

  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double steps = std::max(1, p.steps);
  return {{"target_triangles", triangles},
          {"vertices", r.mesh.numVertices()},
          {"triangles", r.mesh.numTriangles()},
          {"threads", omp_get_max_threads()},
          {"steps", p.steps},
          {"stalled", p.stalled},
          {"residual_drop", p.finalResidual > 0 ? p.initialResidual / p.finalResidual : 0.0},
          {"seconds",
           {{"initial_placement", p.secondsInitial},
            {"dynamics", p.secondsDynamics},
            {"dynamics_per_step", p.secondsDynamics / steps},
            {"adjacency", p.secondsAdjacency},
            {"population", p.secondsPopulation},
            {"connection", c.secondsLocalMeshes + c.secondsRepair},
            {"validation", r.stats.secondsValidate},
            {"whole_mesh", whole},
            {"write_mesh", writeMesh},
            {"write_vtu", writeVtu},
            {"p1_assembly", s.stats.assemblySeconds},
            {"p1_solve", s.stats.solveSeconds}}},
          {"peak_memory_mb", double(ru.ru_maxrss) / 1024.0}};
}

std::string machine() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream o;
  o << model << ", " << ::sysconf(_SC_NPROCESSORS_ONLN) << " cores";
  return o.str();
}

/// Least-squares slope of log y against log x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = int(x.size());
  if (n < 2) return std::nan("");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double a = std::log(x[i]), b = std::log(std::max(y[i], 1e-12));
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int table(const std::vector<std::string>& inputs, const std::string& mdPath, const std::string& jsonPath) {
  std::vector<nlohmann::json> runs;
  for (const auto& f : inputs) {
    std::ifstream in(f);
    if (!in) return fail("cannot read '" + f + "'");
    try {
      runs.push_back(nlohmann::json::parse(in));
    } catch (const std::exception& e) { return fail(f + ": " + e.what()); }
  }
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a["triangles"] < b["triangles"]; });
  const char* stages[][2] = {{"initial_placement", "initial placement"},
                             {"dynamics", "dynamics"},
                             {"dynamics_per_step", "dynamics per step"},
                             {"adjacency", "adjacency upkeep"},
                             {"population", "population control"},
                             {"connection", "ABLMG connection"},
                             {"validation", "validation"},
                             {"whole_mesh", "**whole mesh**"},
                             {"write_mesh", ".mesh write"},
                             {"write_vtu", ".vtu write"},
                             {"p1_assembly", "P1 assembly"},
                             {"p1_solve", "CHOLMOD solve"}};
  std::vector<double> tri;
  for (const auto& r : runs) tri.push_back(r["triangles"].get<double>());
  std::ostringstream md;
  std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  md << "Benchmark suite (`scripts/bench.sh`), " << date << ", " << machine() << ", "
     << runs.front()["threads"].get<int>() << " OpenMP threads. Constant anisotropic metric on the radius-10 disk.\n\n";
  md << "| stage |";
  for (const auto& r : runs) md << " " << r["triangles"].get<long>() << " triangles: s (µs/triangle) |";
  md << " exponent (fit) | exponent (last two) |\n|---|";
  for (std::size_t k = 0; k < runs.size(); ++k) md << "---|";
  md << "---|---|\n";
  nlohmann::json out = {
      {"machine", machine()}, {"date", date}, {"runs", runs}, {"exponents", nlohmann::json::object()}};
  for (const auto& [key, label] : stages) {
    std::vector<double> t;
    for (const auto& r : runs) t.push_back(r["seconds"][key].get<double>());
    const double fit = slope(tri, t);
    const std::size_t n = t.size();
    const double last =
        n >= 2 ? std::log(std::max(t[n - 1], 1e-12) / std::max(t[n - 2], 1e-12)) / std::log(tri[n - 1] / tri[n - 2])
               : std::nan("");
    md << "| " << label << " |";
    char cell[64];
    for (std::size_t k = 0; k < n; ++k) {
      std::snprintf(cell, sizeof cell, " %.3g (%.3g) |", t[k], 1e6 * t[k] / tri[k]);
      md << cell;
    }
    std::snprintf(cell, sizeof cell, " %.2f | %.2f |\n", fit, last);
    md << cell;
    out["exponents"][key] = {{"fit", fit}, {"last_two", last}};
  }
  md << "| steps |";
  for (const auto& r : runs) md << " " << r["steps"].get<int>() << " |";
  md << " | |\n| peak memory (MB) |";
  for (const auto& r : runs) {
    char cell[32];
    std::snprintf(cell, sizeof cell, " %.0f |", r["peak_memory_mb"].get<double>());
    md << cell;
  }
  md << " | |\n";
  std::cout << md.str();
  if (!mdPath.empty()) std::ofstream(mdPath) << md.str();
  if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(2) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return fail("no arguments");
  try {
    if (args[0] == "--triangles") {
      if (args.size() != 4 || args[2] != "--json") return fail("expected --triangles N --json OUT.json");
      const double n = std::stod(args[1]);
      if (!(n >= 100 && n <= 1e8)) return fail("--triangles must be in [100, 1e8], got " + args[1]);
      const nlohmann::json j = runSize(n);
      std::ofstream(args[3]) << j.dump(2) << "\n";
      std::cout << j.dump() << "\n";
      return 0;
    }
    if (args[0] == "--table") {
      std::vector<std::string> inputs;
      std::string md, json;
      for (std::size_t k = 1; k < args.size(); ++k) {
        if (args[k] == "--md" && k + 1 < args.size())
          md = args[++k];
        else if (args[k] == "--json" && k + 1 < args.size())
          json = args[++k];
        else if (args[k].rfind("--", 0) == 0)
          return fail("unknown option '" + args[k] + "'");
        else
          inputs.push_back(args[k]);
      }
      if (inputs.empty()) return fail("--table needs at least one per-size JSON file");
      return table(inputs, md, json);
    }
    return fail("unknown option '" + args[0] + "'");
  } catch (const std::exception& e) {
    std::cerr << "bench_stages: " << e.what() << "\n";
    return 1;
  }
}
