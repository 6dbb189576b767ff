// ablmg solve CONFIG.json: P1 Poisson solve on a mesh → solution .vtu + error report .json.
//
// The config (every key optional unless marked; an unknown key is an error naming its path):
//   {
//     "mesh": "square.mesh"                       medit file (relative to the config's folder), or
//     "mesh": {"structured": {"nx": 64, "ny": 64, "perturbation": 0.0, "seed": 1},
//              "domain": [x0, y0, x1, y1]}        structured mesh of that rectangle, or of the
//                                                 problem's own domain when "domain" is absent
//     "problem": "wavefront", "params": {"alpha": 50}     a library problem (fem/test_problems), or
//     "problem": {"kappa": "1", "f": "2*pi^2*sin(pi*x)*sin(pi*y)",
//                 "dirichlet": {"1": "0", "default": "0"},   per boundary tag, "default" = all others
//                 "neumann": {"3": "0"},                      flux κ ∂u/∂n per tag
//                 "exact": {"u": "...", "ux": "...", "uy": "..."}}   optional, for errors
//     "solver": {"ordering": "geometric" | "cholmod"},
//     "output": {"vtu": "solution.vtu", "report": "report.json", "sol": "u.sol"}
//                                                 (vtu, report default next to the config; sol
//                                                 — u_h as a medit scalar .sol — only if given)
//   }
// Expressions are muparser in x, y (constants pi, e).
//
// The report's "solve" object: unknowns, nonzeros (of A), factor_nonzeros and factor_flops
// (CHOLMOD's counts for the factor L: load-independent, so orderings compare by them),
// dirichlet_vertices, relative_residual, and wall seconds: t_assembly, t_solve = t_ordering +
// t_symbolic (permuted matrices, CHOLMOD's analysis) + t_numeric (factorisation) +
// t_triangular (the solves), plus the residual's evaluation.
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/problem_config.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/vtu.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>

namespace ablmg::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

Mesh2 meshOf(const json& config, const ProblemSetup& setup, const fs::path& base, const std::string& src, json& echo) {
  ABLMG_REQUIRE(config.contains("mesh"), src << ": mesh: missing (a .mesh file or {\"structured\": ...})");
  const json& m = config["mesh"];
  if (m.is_string()) {
    const fs::path file = base / m.get<std::string>();
    echo = file.string();
    return io::readMesh(file.string());
  }
  requireKeys(m, src + ": mesh", {"structured", "domain"});
  ABLMG_REQUIRE(m.contains("structured"), src << ": mesh: needs \"structured\" (or give a file name)");
  const json& st = m["structured"];
  requireKeys(st, src + ": mesh.structured", {"nx", "ny", "perturbation", "seed"});
  // Typed reads: a wrong type is an error naming the key, not a JSON library message.
  const auto integer = [&](const json& j, const char* key, long long fallback, long long lo, long long hi) {
    if (!j.contains(key)) return fallback;
    ABLMG_REQUIRE(j[key].is_number_integer() && j[key].get<long long>() >= lo && j[key].get<long long>() <= hi,
                  src << ": mesh.structured." << key << ": expected an integer in [" << lo << ", " << hi << "], got "
                      << j[key].dump());
    return j[key].get<long long>();
  };
  const int nx = int(integer(st, "nx", 32, 1, 100000)), ny = int(integer(st, "ny", nx, 1, 100000));
  double perturbation = 0;
  if (st.contains("perturbation")) {
    ABLMG_REQUIRE(st["perturbation"].is_number() && std::isfinite(st["perturbation"].get<double>()),
                  src << ": mesh.structured.perturbation: expected a number, got " << st["perturbation"].dump());
    perturbation = st["perturbation"].get<double>();
  }
  const auto seed = std::uint64_t(integer(st, "seed", 1, 0, std::numeric_limits<long long>::max()));
  ABLMG_REQUIRE(double(nx) * double(ny) <= 2.5e7,
                src << ": mesh.structured: nx × ny = " << double(nx) * double(ny) << " cells (at most 2.5e7)");
  Domain domain;
  if (m.contains("domain")) {
    const json& d = m["domain"];
    ABLMG_REQUIRE(
        d.is_array() && d.size() == 4 && std::all_of(d.begin(), d.end(), [](const json& x) { return x.is_number(); }),
        src << ": mesh.domain: expected [x0, y0, x1, y1] (numbers), got " << d.dump());
    const double c[4] = {d[0].get<double>(), d[1].get<double>(), d[2].get<double>(), d[3].get<double>()};
    ABLMG_REQUIRE(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3]) &&
                      c[0] < c[2] && c[1] < c[3],
                  src << ": mesh.domain: need x0 < x1 and y0 < y1, got " << d.dump());
    domain = Domain::rectangle(c[0], c[1], c[2], c[3]);
  } else {
    ABLMG_REQUIRE(setup.domain.has_value(), src << ": mesh.domain: needed for an expression problem");
    domain = *setup.domain;
  }
  echo = {{"structured", {{"nx", nx}, {"ny", ny}, {"perturbation", perturbation}, {"seed", seed}}}};
  return fem::structuredMesh(domain, nx, ny, perturbation, seed);
}

/// config["solver"]["ordering"] into options; returns its name.
std::string readSolverOptions(const json& config, const std::string& src, fem::SolveOptions& options) {
  std::string ordering = "geometric";
  if (!config.contains("solver")) return ordering;
  requireKeys(config["solver"], src + ": solver", {"ordering"});
  if (config["solver"].contains("ordering")) {
    const json& o = config["solver"]["ordering"];
    ABLMG_REQUIRE(o.is_string(), src << ": solver.ordering: expected a string, got " << o.dump());
    ordering = o.get<std::string>();
  }
  ABLMG_REQUIRE(ordering == "geometric" || ordering == "metis" || ordering == "cholmod",
                src << ": solver.ordering: '" << ordering << "' (valid: geometric, metis, cholmod)");
  options.ordering = ordering == "geometric" ? fem::Ordering::GeometricNestedDissection
                     : ordering == "metis"   ? fem::Ordering::Metis
                                             : fem::Ordering::Cholmod;
  return ordering;
}

struct SolveOutputs {
  std::string vtu, report, sol;  ///< sol empty: not written
};

/// config["output"], paths relative to the config's folder.
SolveOutputs readOutputs(const json& config, const std::string& src, const fs::path& base) {
  SolveOutputs out{(base / "solution.vtu").string(), (base / "report.json").string(), ""};
  if (!config.contains("output")) return out;
  const json& o = config["output"];
  requireKeys(o, src + ": output", {"vtu", "report", "sol"});
  const auto path = [&](const char* key, std::string& to) {
    if (!o.contains(key)) return;
    ABLMG_REQUIRE(o[key].is_string() && !o[key].get<std::string>().empty(),
                  src << ": output." << key << ": expected a file name, got " << o[key].dump());
    to = (base / o[key].get<std::string>()).string();
  };
  path("vtu", out.vtu);
  path("report", out.report);
  path("sol", out.sol);
  return out;
}

/// Errors against the exact solution into the report and the .vtu's fields (u_exact, u_h − u,
/// per-triangle L2 and H1 errors).
void addErrors(const Mesh2& mesh, const fem::PoissonSolution& sol, const fem::ExactSolution& exact, json& report,
               std::vector<io::Field>& pointFields, std::vector<io::Field>& cellFields) {
  const fem::ErrorReport err = fem::computeErrors(mesh, sol.u, exact);
  report["errors"] = {{"l2", err.l2}, {"l2_interp", err.l2Interp}, {"max_vertex", err.maxVertex}};
  if (exact.grad) report["errors"]["h1"] = err.h1;
  std::printf("L2=%.4e max=%.4e L2(I_h u)=%.4e", err.l2, err.maxVertex, err.l2Interp);
  if (exact.grad) std::printf(" H1=%.4e", err.h1);
  std::printf("\n");
  const Eigen::VectorXd ui = fem::interpolate(mesh, exact.u);
  std::vector<double> diff(ui.size());
  for (Eigen::Index v = 0; v < ui.size(); ++v) diff[v] = sol.u[v] - ui[v];
  pointFields.push_back({"u_exact", 1, std::vector<double>(ui.data(), ui.data() + ui.size())});
  pointFields.push_back({"u_h_minus_u", 1, std::move(diff)});
  cellFields.push_back({"error_l2", 1, err.elementL2});
  if (exact.grad) cellFields.push_back({"error_h1", 1, err.elementH1});
}

int runSolve(const std::vector<std::string>& args) {
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << "usage: ablmg solve CONFIG.json\n"
                 "  P1 finite elements for -div(kappa grad u) = f, CHOLMOD; writes the solution (.vtu)\n"
                 "  and a JSON report (unknowns, times, errors when the exact solution is known).\n"
                 "  See the comment at the top of cli/cmd_solve.cpp for the config keys.\n";
    return 0;
  }
  ABLMG_REQUIRE(args.size() == 1, "usage: ablmg solve CONFIG.json (got " << args.size() << " arguments)");
  const std::string src = args[0];
  const json config = readJsonFile(src);
  requireKeys(config, src, {"mesh", "problem", "params", "solver", "output"});
  ABLMG_REQUIRE(config.contains("problem"), src << ": problem: missing");
  const fs::path base = fs::path(src).parent_path();

  // 1. Problem and mesh.
  const ProblemSetup setup = problemFromJson(config, src);
  json meshEcho;
  const Mesh2 mesh = meshOf(config, setup, base, src, meshEcho);
  mesh.requireValid(src + ": mesh");

  // 2. Solver options and outputs.
  fem::SolveOptions options;
  const std::string ordering = readSolverOptions(config, src, options);
  const SolveOutputs out = readOutputs(config, src, base);
  json report = {{"config", src},
                 {"resolved",
                  {{"mesh", meshEcho},
                   {"problem", setup.echo},
                   {"solver", {{"ordering", ordering}}},
                   {"output", {{"vtu", out.vtu}, {"report", out.report}, {"sol", out.sol}}}}}};
  std::cout << "ablmg solve: " << report["resolved"].dump() << "\n";

  // 3. Assemble and solve.
  const fem::PoissonSolution sol = fem::solvePoisson(mesh, setup.problem, options);
  report["mesh"] = {{"vertices", mesh.numVertices()}, {"triangles", mesh.numTriangles()}};
  report["solve"] = {{"unknowns", sol.stats.unknowns},
                     {"nonzeros", sol.stats.nonZeros},
                     {"factor_nonzeros", sol.stats.factorNonZeros},
                     {"factor_flops", sol.stats.factorFlops},
                     {"dirichlet_vertices", sol.stats.dirichletVertices},
                     {"t_assembly", sol.stats.assemblySeconds},
                     {"t_solve", sol.stats.solveSeconds},
                     {"t_ordering", sol.stats.orderingSeconds},
                     {"t_symbolic", sol.stats.symbolicSeconds},
                     {"t_numeric", sol.stats.numericSeconds},
                     {"t_triangular", sol.stats.triangularSeconds},
                     {"relative_residual", sol.stats.residual}};
  std::printf("N=%d unknowns=%d nnz=%ld t_assembly=%.3fs t_solve=%.3fs (ordering %.3f, factorisation %.3f, "
              "%.3g GFlop)\n",
              mesh.numVertices(), sol.stats.unknowns, sol.stats.nonZeros, sol.stats.assemblySeconds,
              sol.stats.solveSeconds, sol.stats.orderingSeconds,
              sol.stats.symbolicSeconds + sol.stats.numericSeconds, sol.stats.factorFlops * 1e-9);

  // 4. Errors against the exact solution, when known.
  std::vector<io::Field> pointFields{{"u_h", 1, std::vector<double>(sol.u.data(), sol.u.data() + sol.u.size())}};
  std::vector<io::Field> cellFields;
  if (setup.exact.u) addErrors(mesh, sol, setup.exact, report, pointFields, cellFields);

  // 5. Outputs, each atomic; all or nothing.
  std::vector<std::string> written;
  try {
    io::writeVtu(out.vtu, mesh, pointFields, cellFields);
    written.push_back(out.vtu);
    if (!out.sol.empty()) {
      io::writeScalarSol(out.sol, std::span<const double>(sol.u.data(), std::size_t(sol.u.size())));
      written.push_back(out.sol);
    }
    io::writeFileAtomically(out.report, [&](std::ostream& os) { os << report.dump(2) << "\n"; });
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    throw;
  }
  std::cout << "wrote " << out.vtu << (out.sol.empty() ? "" : ", " + out.sol) << " and " << out.report << "\n";
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("solve", "P1 Poisson solve (CHOLMOD): mesh + problem -> solution .vtu + error report",
              ablmg::cli::runSolve)
