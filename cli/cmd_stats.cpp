// ablmg stats MESH.mesh [metric] [--e E] [--json [OUT.json]]: quality report of a medit mesh
// (mesher/quality.hpp; paper §4.2 Table 1 and §6 Table 2).
//
//   metric (at most one; default: the identity, i.e. Euclidean lengths and shape quality):
//     --sol METRIC.sol            per-vertex tensors (type 3) or sizes (type 1), 2D only
//     --metric CONFIG.json        the "metric" of an `ablmg mesh` config, or a bare metric
//                                 object (expressions or background mesh + .sol), 2D only
//     --metric-expr H1 H2 THETA   muparser expressions in x, y (sizes and angle, eq. 2), 2D only
//     --h H                       isotropic size H (2D: M = I/H²; 3D surfaces: M3 = I/H², eq. 17)
//   --e E         bin width of the edge-deviation histogram (default 0.05, as in the paper)
//   --json FILE   also write the report as JSON (FILE must end in .json)
//   --json        print the report as JSON on stdout instead of text
//
// A file whose vertices all have z = 0 is a 2D mesh (Mesh2, validated with Mesh2::validate);
// otherwise a 3D surface mesh (checked with checkManifold; elements measured by Lee's α).
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/cli/config.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/mesher/quality.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

namespace ablmg::cli {
namespace {

using nlohmann::json;

constexpr const char* kUsage =
    "usage: ablmg stats MESH.mesh [--sol METRIC.sol | --metric CONFIG.json | --metric-expr H1 H2 THETA | --h H]\n"
    "                   [--e E] [--json [OUT.json]]\n"
    "  Edge metric lengths and deviation eps = |l-1| (paper eq. 13, Table 1), element quality\n"
    "  q = 4*sqrt(3)*A_M/sum(l^2) in 2D or Lee's alpha (eqs. 19-20) on 3D surfaces (Table 2),\n"
    "  and mesh validity. Without a metric: the identity (Euclidean lengths).\n"
    "  --sol FILE          per-vertex sizes (type 1) or tensors (type 3, m11 m12 m22)\n"
    "  --metric CONFIG     the metric of an `ablmg mesh` config (or a bare metric object)\n"
    "  --metric-expr H1 H2 THETA   sizes and angle as expressions in x, y\n"
    "  --h H               isotropic size (3D surfaces: the only choice)\n"
    "  --e E               bin width of the edge-deviation histogram (default 0.05)\n"
    "  --json OUT.json     also write the report as JSON; --json alone: JSON on stdout, no text\n";

struct Args {
  std::string mesh, sol, json, metricConfig;
  bool jsonToStdout = false;
  std::vector<std::string> expr;  ///< h1, h2, theta
  std::optional<double> h;
  double e = 0.05;
};

Args parse(const std::vector<std::string>& args) {
  Args a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& f = args[i];
    auto value = [&](int k) -> const std::string& {
      ABLMG_REQUIRE(i + k < args.size(), f << ": missing value (" << kUsage << ")");
      return args[i + k];
    };
    if (f == "--sol")
      a.sol = value(1), ++i;
    else if (f == "--json") {
      // A value only if it names a .json file: `--json` alone (or before another flag or the
      // mesh) prints the report as JSON on stdout.
      if (i + 1 < args.size() && args[i + 1].ends_with(".json") && !args[i + 1].starts_with("-"))
        a.json = args[++i];
      else
        a.jsonToStdout = true;
    } else if (f == "--metric")
      a.metricConfig = value(1), ++i;
    else if (f == "--h")
      a.h = parsePositiveNumber(value(1), "stats: " + f), ++i;
    else if (f == "--e")
      a.e = parsePositiveNumber(value(1), "stats: " + f), ++i;
    else if (f == "--metric-expr")
      a.expr = {value(1), value(2), value(3)}, i += 3;
    else if (f.starts_with("-"))
      ABLMG_REQUIRE(false, "unknown option '" << f << "' (see ablmg stats --help)");
    else {
      ABLMG_REQUIRE(a.mesh.empty(), "more than one mesh given ('" << a.mesh << "', '" << f << "')");
      a.mesh = f;
    }
  }
  ABLMG_REQUIRE(!a.mesh.empty(), "no mesh given (usage: ablmg stats MESH.mesh [options])");
  ABLMG_REQUIRE(int(!a.sol.empty()) + int(!a.metricConfig.empty()) + int(!a.expr.empty()) + int(a.h.has_value()) <= 1,
                "give at most one of --sol, --metric, --metric-expr, --h");
  ABLMG_REQUIRE(a.json.empty() || !a.jsonToStdout, "--json given twice (once with a file, once without)");
  return a;
}

int runStats(const std::vector<std::string>& args) {
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  const Args a = parse(args);

  // 1. Read the mesh; 2D unless some vertex leaves the plane z = 0.
  const io::SurfaceMeshFile file = io::readSurfaceMesh(a.mesh);
  const bool surface =
      std::any_of(file.vertices.begin(), file.vertices.end(), [](const auto& p) { return p.z() != 0; });
  json report = {{"mesh", a.mesh}, {"e", a.e}};
  mesher::MeshQuality q;

  // 2. The metric, then the figures.
  if (surface) {
    ABLMG_REQUIRE(a.sol.empty() && a.expr.empty() && a.metricConfig.empty(),
                  a.mesh << ": a 3D surface mesh takes only --h (isotropic M3); --sol/--metric/--metric-expr are 2D");
    const double h = a.h.value_or(1.0);
    report["metric"] = a.h ? "isotropic M3 = I/h^2, h = " + std::to_string(h) : "identity (Euclidean lengths)";
    mesher::SurfaceMesh s;
    s.vertices = file.vertices;
    s.triangles = file.triangles;
    q = mesher::surfaceQuality(s, mesher::isotropicMetric3(h), a.e);
  } else {
    const Mesh2 mesh = io::readMesh(a.mesh);
    std::vector<Metric2> metrics(mesh.numVertices());  // identity unless a metric is given
    if (!a.sol.empty()) {
      metrics = io::readSol(a.sol, mesh.numVertices());
      report["metric"] = "per-vertex tensors from " + a.sol;
    } else if (!a.metricConfig.empty()) {
      std::string description;
      const auto field = loadMetricConfig(a.metricConfig, description);
      field->evaluate(mesh.vertices, metrics);
      report["metric"] = description + " (from " + a.metricConfig + ")";
    } else if (!a.expr.empty()) {
      const AnalyticMetricField field(AnalyticMetricField::Form::Sizes, a.expr[0], a.expr[1], a.expr[2],
                                      "--metric-expr");
      field.evaluate(mesh.vertices, metrics);
      report["metric"] = "h1 = " + a.expr[0] + ", h2 = " + a.expr[1] + ", theta = " + a.expr[2];
    } else if (a.h) {
      std::fill(metrics.begin(), metrics.end(), Metric2::isotropic(*a.h));
      report["metric"] = "isotropic M = I/h^2, h = " + std::to_string(*a.h);
    } else {
      report["metric"] = "identity (Euclidean lengths)";
    }
    q = mesher::meshQuality(mesh, metrics, a.e);
  }
  report["quality"] = cli::qualityJson(q);

  // 3. Print, and write the JSON report if asked.
  if (a.jsonToStdout) {
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  std::cout << "ablmg stats: " << a.mesh << ", metric: " << report["metric"].get<std::string>() << "\n"
            << mesher::toText(q);
  if (!a.json.empty()) {
    io::writeFileAtomically(a.json, [&](std::ostream& os) { os << report.dump(2) << "\n"; });
    std::cout << "wrote " << a.json << "\n";
  }
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("stats", "quality report of a mesh: metric edge lengths, element quality", ablmg::cli::runStats)
