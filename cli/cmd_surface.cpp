// ablmg surface --surface NAME --h H -o OUT.mesh [--vtu OUT.vtu] [--stl OUT.stl]
//               [--png-param OUT.png] [--png-3d OUT.png] [--json R.json] [--seed N]
// ablmg surface CONFIG.json [same output flags; --h, --seed override the config]
// ablmg surface --list
//
// Parametric surface triangulation by the mapping method (paper §5–6): the parameter domain
// of a surface is meshed with the induced metric M2 = Jᵀ M3 J (eq. 16) of the isotropic 3D
// size h (eq. 17), the mesh is mapped back to 3D and written; the report gives Lee's quality
// α (eqs. 19–20, Table 2 bins) and the 3D edge lengths relative to h.
//
// A surface config (every key but "surface" optional; unknown keys are errors naming the path):
//   {"surface": "paper-fig16"                                   a built-in, or
//    "surface": {"x": "u", "y": "v", "z": "cos(pi*(u^2+v^2))^2",  muparser in u, v (pi)
//                "u": [-1, 1], "v": [-1, 1],                      over [u0,u1]×[v0,v1];
//                "weld": false},                                   true: weld the sides that r maps
//                                                                  onto each other (periodic r)
//    "h": 0.05, "seed": 0,
//    "options": {"placement": {...}, "connect": {...}}}         as in `ablmg mesh` configs
// Errors are exceptions (one line, exit 1); output paths are checked before meshing and the
// files are written only once the mesh exists, each atomically.
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/cli/progress_line.hpp"
#include "ablmg/cli/config.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/stl.hpp"
#include "ablmg/io/surface_picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"
#include "ablmg/mesher/surface.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace ablmg::cli {
namespace {

using nlohmann::json;

const char* kHelp = R"(usage: ablmg surface --surface NAME --h H -o OUT.mesh [--vtu OUT.vtu] [--stl OUT.stl]
                     [--png-param OUT.png] [--png-3d OUT.png] [--json R.json] [--seed N]
       ablmg surface CONFIG.json [the same outputs; --h and --seed override the config]
       ablmg surface --list

Meshes a parametric surface r(u,v) by the mapping method (paper §5–6): the (u,v) domain is
meshed with M2 = J^T M3 J (eq. 16) for the isotropic 3D size H (eq. 17), then mapped to 3D.
  --surface NAME   a built-in surface (--list shows them with formulas and (u,v) domains)
  CONFIG.json      {"surface": NAME | {"x","y","z": exprs in u,v, "u": [u0,u1], "v": [v0,v1]},
                    "h": H, "seed": N, "options": {"placement": {...}, "connect": {...}}}
  --h H            target 3D edge length (> 0)
  -o OUT.mesh      medit surface mesh (Dimension 3)
  --vtu, --stl     3D .vtu (Lee's quality as cell data) and STL outputs
  --png-param PNG  the parameter-space mesh coloured by Lee's quality
  --png-3d PNG     a shaded view of the 3D mesh (orthographic, Lambert shading)
  --json R.json    report: options, counts, quality distribution, edge lengths, manifold check, times
  --print-options  print the options in effect (JSON: surface, h and the mesher's, the "mesh"
                   preset with the config's options) and exit; no output is needed
  --seed N         placement seed: 0 (default) the nodes as placed; N > 0 a different mesh of
                   the same statistics, the same for the same N
  -v N             0: no progress line on stderr (shown on a terminal only; default 1)
)";

/// The extension must match and the folder must exist — checked before the (long) meshing.
void checkOutput(const std::string& path, const char* ext, const char* flag) {
  namespace fs = std::filesystem;
  ABLMG_REQUIRE(fs::path(path).extension() == ext, "surface: " << flag << " '" << path << "' must end in " << ext);
  const fs::path dir = fs::path(path).parent_path();
  ABLMG_REQUIRE(dir.empty() || fs::is_directory(dir),
                "surface: " << flag << " '" << path << "': folder " << dir.string() << " does not exist");
}

struct SurfaceSetup {
  std::unique_ptr<mesher::ParametricSurface> surface;
  std::string name;
  double h = 0;
  long long seed = 0;
  mesher::MeshOptions options;
  std::string preset = "mesh";  ///< options.preset of the config, else "mesh"
};

/// Reads a surface config (see the header comment); errors name the file and key path.
SurfaceSetup loadSurfaceConfig(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  ABLMG_REQUIRE(in, path << ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  json j;
  try {
    j = json::parse(ss.str());
  } catch (const json::exception& e) {
    std::string msg = e.what();
    const auto p = msg.find("] ");
    ABLMG_REQUIRE(false, path << ": invalid JSON: " << (p == std::string::npos ? msg : msg.substr(p + 2)));
  }
  ABLMG_REQUIRE(j.is_object(), path << ": expected an object, got " << j.type_name());
  for (const auto& [key, value] : j.items())
    ABLMG_REQUIRE(key == "surface" || key == "h" || key == "seed" || key == "options",
                  path << ": unknown key '" << key << "' (valid: surface, h, seed, options)");
  ABLMG_REQUIRE(j.contains("surface"), path << ": surface: missing (required)");
  SurfaceSetup s;
  const json& sj = j["surface"];
  if (sj.is_string()) {
    s.name = sj.get<std::string>();
    s.surface = mesher::makeBuiltinSurface(s.name);
  } else {
    const std::string w = path + ": surface";
    ABLMG_REQUIRE(sj.is_object(),
                  w << ": expected a built-in name or an object {x, y, z, u, v}, got " << sj.type_name());
    for (const auto& [key, value] : sj.items())
      ABLMG_REQUIRE(key == "x" || key == "y" || key == "z" || key == "u" || key == "v" || key == "weld",
                    w << ": unknown key '" << key << "' (valid: x, y, z, u, v, weld)");
    bool weld = false;
    if (sj.contains("weld")) {
      ABLMG_REQUIRE(sj["weld"].is_boolean(), w << ".weld: expected true or false");
      weld = sj["weld"].get<bool>();
    }
    std::string e[3];
    const char* names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      ABLMG_REQUIRE(sj.contains(names[k]) && sj[names[k]].is_string(),
                    w << "." << names[k] << ": expected an expression string in u, v");
      e[k] = sj[names[k]].get<std::string>();
    }
    double range[2][2];
    const char* uv[2] = {"u", "v"};
    for (int k = 0; k < 2; ++k) {
      const json& r = sj.contains(uv[k]) ? sj[uv[k]] : json();
      ABLMG_REQUIRE(r.is_array() && r.size() == 2 && r[0].is_number() && r[1].is_number(),
                    w << "." << uv[k] << ": expected [min, max]");
      range[k][0] = r[0].get<double>(), range[k][1] = r[1].get<double>();
      ABLMG_REQUIRE(std::isfinite(range[k][0]) && std::isfinite(range[k][1]) && range[k][0] < range[k][1],
                    w << "." << uv[k] << ": expected min < max, got [" << range[k][0] << ", " << range[k][1] << "]");
    }
    s.surface =
        mesher::makeExpressionSurface(e[0], e[1], e[2], range[0][0], range[1][0], range[0][1], range[1][1], w, weld);
    s.name = std::filesystem::path(path).stem().string();
  }
  if (j.contains("h")) {
    ABLMG_REQUIRE(j["h"].is_number() && j["h"].get<double>() > 0 && std::isfinite(j["h"].get<double>()),
                  path << ": h: expected a positive number");
    s.h = j["h"].get<double>();
  }
  if (j.contains("seed")) {
    ABLMG_REQUIRE(j["seed"].is_number_integer() && j["seed"].get<long long>() >= 0,
                  path << ": seed: expected an integer >= 0");
    s.seed = j["seed"].get<long long>();
  }
  if (j.contains("options")) {
    applyMeshOptions(j["options"], s.options, path + ": options");
    if (j["options"].contains("preset")) s.preset = j["options"]["preset"].get<std::string>();
  }
  return s;
}

int runSurface(const std::vector<std::string>& args) {
  std::string name, configPath, meshPath, vtuPath, stlPath, pngPath, png3dPath, jsonPath;
  double h = 0;
  long long seed = -1;
  int verbosity = 1;
  bool printOptions = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size(), "surface: " << a << " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      std::cout << kHelp;
      return 0;
    } else if (a == "--list") {
      for (const auto& line : mesher::builtinSurfaceList()) std::cout << line << "\n";
      return 0;
    } else if (a == "--surface") {
      name = value();
    } else if (a == "--h") {
      h = parsePositiveNumber(value(), "surface: --h");
    } else if (a == "-o") {
      meshPath = value();
    } else if (a == "--vtu") {
      vtuPath = value();
    } else if (a == "--stl") {
      stlPath = value();
    } else if (a == "--png-param") {
      pngPath = value();
    } else if (a == "--png-3d") {
      png3dPath = value();
    } else if (a == "--json") {
      jsonPath = value();
    } else if (a == "-v") {
      verbosity = int(parseInteger(value(), "surface: -v", 0, 10));
    } else if (a == "--seed") {
      seed = parseInteger(value(), "surface: --seed", 0, std::numeric_limits<long long>::max());
    } else if (a == "--print-options") {
      printOptions = true;
    } else if (!a.empty() && a[0] != '-' && configPath.empty()) {
      configPath = a;
    } else {
      ABLMG_REQUIRE(false, "surface: unknown argument '" << a << "' (see ablmg surface --help)");
    }
  }
  ABLMG_REQUIRE(name.empty() != configPath.empty(),
                "surface: give either --surface NAME or CONFIG.json (ablmg surface --list, --help)");
  ABLMG_REQUIRE(printOptions || !meshPath.empty() || !vtuPath.empty() || !stlPath.empty() || !pngPath.empty() ||
                    !png3dPath.empty() || !jsonPath.empty(),
                "surface: no output (give -o OUT.mesh, --vtu, --stl, --png-param, --png-3d or --json)");
  if (!meshPath.empty()) checkOutput(meshPath, ".mesh", "-o");
  if (!vtuPath.empty()) checkOutput(vtuPath, ".vtu", "--vtu");
  if (!stlPath.empty()) checkOutput(stlPath, ".stl", "--stl");
  if (!pngPath.empty()) checkOutput(pngPath, ".png", "--png-param");
  if (!png3dPath.empty()) checkOutput(png3dPath, ".png", "--png-3d");
  if (!jsonPath.empty()) checkOutput(jsonPath, ".json", "--json");

  SurfaceSetup setup;
  if (!configPath.empty()) {
    setup = loadSurfaceConfig(configPath);
  } else {
    setup.name = name;
    setup.surface = mesher::makeBuiltinSurface(name);
  }
  if (h > 0) setup.h = h;
  if (seed >= 0) setup.seed = seed;
  if (printOptions) {
    setup.options.placement.seed = std::uint64_t(setup.seed);
    printEffectiveOptions("surface", setup.preset, setup.options,
                          {{"surface", setup.name}, {"h", setup.h}, {"config", configPath}});
    return 0;
  }
  ABLMG_REQUIRE(setup.h > 0, "surface: --h H is required" << (configPath.empty() ? "" : " (or \"h\" in the config)"));
  const mesher::Metric3Field m3 = mesher::isotropicMetric3(setup.h);
  const mesher::InducedMetricField m2(*setup.surface, m3);
  setup.options.placement.seed = std::uint64_t(setup.seed);
  const json optionsEcho = {{"surface", setup.name},
                            {"description", setup.surface->description()},
                            {"h", setup.h},
                            {"seed", setup.seed},
                            {"mesher", meshOptionsToJson(setup.options)}};
  std::cout << "ablmg surface: options " << optionsEcho.dump() << "\n";

  // Mesh (u,v) with M2, map to 3D, measure.
  ProgressLine progress("surface", verbosity);
  setup.options.progress = progress.callback();
  const Stopwatch watch;
  const mesher::MeshResult r = mesher::meshDomain(setup.surface->parameterDomain(), m2, setup.options);
  progress.clear();
  const mesher::SurfaceMesh s = mesher::mapToSurface(r.mesh, *setup.surface);
  const double seconds = watch.seconds();
  const mesher::MeshQuality q = mesher::surfaceQuality(s, m3);
  ABLMG_REQUIRE(q.valid, "surface: the 3D mesh is not a consistently oriented manifold: " << q.firstProblem);
  const std::vector<double> alpha = mesher::leeQuality(s, m3);
  const long boundaryEdges = mesher::countBoundaryEdges(s);
  const long welded = long(r.mesh.numVertices()) - long(s.vertices.size());  // seam vertices merged (periodic surfaces)

  std::vector<std::string> written;
  try {
    if (!meshPath.empty()) {
      io::writeSurfaceMesh(meshPath, s.vertices, s.triangles);
      written.push_back(meshPath);
    }
    if (!vtuPath.empty()) {
      io::writeVtu(vtuPath, s.vertices, s.triangles, {}, {io::Field{"lee_quality", 1, alpha}});
      written.push_back(vtuPath);
    }
    if (!stlPath.empty()) {
      io::writeStl(stlPath, s.vertices, s.triangles, setup.name);
      written.push_back(stlPath);
    }
    if (!pngPath.empty()) {
      io::drawMesh(pngPath, r.mesh, alpha, "Lee quality");
      written.push_back(pngPath);
    }
    if (!png3dPath.empty()) {
      io::drawSurface(png3dPath, s.vertices, s.triangles);
      written.push_back(png3dPath);
    }
    if (!jsonPath.empty()) {
      json j = {{"options", optionsEcho},          {"seconds", seconds},        {"quality", cli::qualityJson(q)},
                {"boundary_edges", boundaryEdges}, {"welded_vertices", welded}, {"outputs", written}};
      io::writeFileAtomically(jsonPath, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
      written.push_back(jsonPath);
    }
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    throw;
  }
  std::cout << "ablmg surface: " << setup.name << ", h = " << setup.h << ": " << q.vertices << " vertices, "
            << q.triangles << " triangles in " << seconds << " s; manifold: yes; boundary edges: " << boundaryEdges
            << (welded > 0 ? "; seams welded: " + std::to_string(welded) + " vertices merged" : std::string()) << "\n"
            << mesher::toText(q);
  for (const auto& w : written) std::cout << "  -> " << w << "\n";
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("surface", "mesh a parametric surface (paper §5-6): --list, --surface NAME --h H, or CONFIG.json",
              ablmg::cli::runSurface)
