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

/// The command line, as parsed. seed < 0: not given (the config's, else 0).
struct SurfaceArgs {
  std::string name, configPath, meshPath, vtuPath, stlPath, pngPath, png3dPath, jsonPath;
  double h = 0;
  long long seed = -1;
  int verbosity = 1;
  bool help = false, list = false, printOptions = false;
};

/// Parses the flags and checks the output paths (before the long meshing); errors name the flag.
SurfaceArgs parseSurfaceArgs(const std::vector<std::string>& args) {
  SurfaceArgs r;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size(), "surface: " << a << " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      r.help = true;
      return r;
    } else if (a == "--list") {
      r.list = true;
      return r;
    } else if (a == "--surface") {
      r.name = value();
    } else if (a == "--h") {
      r.h = parsePositiveNumber(value(), "surface: --h");
    } else if (a == "-o") {
      r.meshPath = value();
    } else if (a == "--vtu") {
      r.vtuPath = value();
    } else if (a == "--stl") {
      r.stlPath = value();
    } else if (a == "--png-param") {
      r.pngPath = value();
    } else if (a == "--png-3d") {
      r.png3dPath = value();
    } else if (a == "--json") {
      r.jsonPath = value();
    } else if (a == "-v") {
      r.verbosity = int(parseInteger(value(), "surface: -v", 0, 10));
    } else if (a == "--seed") {
      r.seed = parseInteger(value(), "surface: --seed", 0, std::numeric_limits<long long>::max());
    } else if (a == "--print-options") {
      r.printOptions = true;
    } else if (!a.empty() && a[0] != '-' && r.configPath.empty()) {
      r.configPath = a;
    } else {
      ABLMG_REQUIRE(false, "surface: unknown argument '" << a << "' (see ablmg surface --help)");
    }
  }
  ABLMG_REQUIRE(r.name.empty() != r.configPath.empty(),
                "surface: give either --surface NAME or CONFIG.json (ablmg surface --list, --help)");
  ABLMG_REQUIRE(r.printOptions || !r.meshPath.empty() || !r.vtuPath.empty() || !r.stlPath.empty() ||
                    !r.pngPath.empty() || !r.png3dPath.empty() || !r.jsonPath.empty(),
                "surface: no output (give -o OUT.mesh, --vtu, --stl, --png-param, --png-3d or --json)");
  if (!r.meshPath.empty()) checkOutput(r.meshPath, ".mesh", "-o");
  if (!r.vtuPath.empty()) checkOutput(r.vtuPath, ".vtu", "--vtu");
  if (!r.stlPath.empty()) checkOutput(r.stlPath, ".stl", "--stl");
  if (!r.pngPath.empty()) checkOutput(r.pngPath, ".png", "--png-param");
  if (!r.png3dPath.empty()) checkOutput(r.png3dPath, ".png", "--png-3d");
  if (!r.jsonPath.empty()) checkOutput(r.jsonPath, ".json", "--json");
  return r;
}

/// What was meshed and measured, for the outputs and the summary.
struct SurfaceOutcome {
  mesher::MeshResult param;  ///< the (u,v) mesh
  mesher::SurfaceMesh surface;
  mesher::MeshQuality quality;
  std::vector<double> alpha;  ///< Lee's quality per triangle
  long boundaryEdges = 0, welded = 0;
  double seconds = 0;
};

/// Writes every requested output, each atomically; on a failure removes those already written.
std::vector<std::string> writeSurfaceOutputs(const SurfaceArgs& a, const SurfaceSetup& setup, const SurfaceOutcome& o,
                                             const json& optionsEcho) {
  const auto& s = o.surface;
  std::vector<std::string> written;
  try {
    if (!a.meshPath.empty()) {
      io::writeSurfaceMesh(a.meshPath, s.vertices, s.triangles);
      written.push_back(a.meshPath);
    }
    if (!a.vtuPath.empty()) {
      io::writeVtu(a.vtuPath, s.vertices, s.triangles, {}, {io::Field{"lee_quality", 1, o.alpha}});
      written.push_back(a.vtuPath);
    }
    if (!a.stlPath.empty()) {
      io::writeStl(a.stlPath, s.vertices, s.triangles, setup.name);
      written.push_back(a.stlPath);
    }
    if (!a.pngPath.empty()) {
      io::drawMesh(a.pngPath, o.param.mesh, o.alpha, "Lee quality");
      written.push_back(a.pngPath);
    }
    if (!a.png3dPath.empty()) {
      io::drawSurface(a.png3dPath, s.vertices, s.triangles);
      written.push_back(a.png3dPath);
    }
    if (!a.jsonPath.empty()) {
      const json j = {{"options", optionsEcho},
                      {"seconds", o.seconds},
                      {"quality", cli::qualityJson(o.quality)},
                      {"boundary_edges", o.boundaryEdges},
                      {"welded_vertices", o.welded},
                      {"outputs", written}};
      io::writeFileAtomically(a.jsonPath, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
      written.push_back(a.jsonPath);
    }
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    throw;
  }
  return written;
}

int runSurface(const std::vector<std::string>& argv) {
  const SurfaceArgs args = parseSurfaceArgs(argv);
  if (args.help || args.list) {
    if (args.help) std::cout << kHelp;
    if (args.list)
      for (const auto& line : mesher::builtinSurfaceList()) std::cout << line << "\n";
    return 0;
  }
  SurfaceSetup setup;
  if (!args.configPath.empty()) {
    setup = loadSurfaceConfig(args.configPath);
  } else {
    setup.name = args.name;
    setup.surface = mesher::makeBuiltinSurface(args.name);
  }
  if (args.h > 0) setup.h = args.h;
  if (args.seed >= 0) setup.seed = args.seed;
  setup.options.placement.seed = std::uint64_t(setup.seed);
  if (args.printOptions) {
    printEffectiveOptions("surface", setup.preset, setup.options,
                          {{"surface", setup.name}, {"h", setup.h}, {"config", args.configPath}});
    return 0;
  }
  ABLMG_REQUIRE(setup.h > 0,
                "surface: --h H is required" << (args.configPath.empty() ? "" : " (or \"h\" in the config)"));
  const mesher::Metric3Field m3 = mesher::isotropicMetric3(setup.h);
  const mesher::InducedMetricField m2(*setup.surface, m3);
  const json optionsEcho = {{"surface", setup.name},
                            {"description", setup.surface->description()},
                            {"h", setup.h},
                            {"seed", setup.seed},
                            {"mesher", meshOptionsToJson(setup.options)}};
  std::cout << "ablmg surface: options " << optionsEcho.dump() << "\n";

  // Mesh (u,v) with M2, map to 3D, measure.
  ProgressLine progress("surface", args.verbosity);
  setup.options.progress = progress.callback();
  const Stopwatch watch;
  SurfaceOutcome o;
  o.param = mesher::meshDomain(setup.surface->parameterDomain(), m2, setup.options);
  progress.clear();
  o.surface = mesher::mapToSurface(o.param.mesh, *setup.surface);
  o.seconds = watch.seconds();
  o.quality = mesher::surfaceQuality(o.surface, m3);
  ABLMG_REQUIRE(o.quality.valid,
                "surface: the 3D mesh is not a consistently oriented manifold: " << o.quality.firstProblem);
  o.alpha = mesher::leeQuality(o.surface, m3);
  o.boundaryEdges = mesher::countBoundaryEdges(o.surface);
  o.welded = long(o.param.mesh.numVertices()) - long(o.surface.vertices.size());  // seams merged (periodic)

  const std::vector<std::string> written = writeSurfaceOutputs(args, setup, o, optionsEcho);
  const auto& q = o.quality;
  std::cout << "ablmg surface: " << setup.name << ", h = " << setup.h << ": " << q.vertices << " vertices, "
            << q.triangles << " triangles in " << o.seconds << " s; manifold: yes; boundary edges: " << o.boundaryEdges
            << (o.welded > 0 ? "; seams welded: " + std::to_string(o.welded) + " vertices merged" : std::string())
            << "\n"
            << mesher::toText(q);
  for (const auto& w : written) std::cout << "  -> " << w << "\n";
  return 0;
}

}  // namespace
}  // namespace ablmg::cli

ABLMG_COMMAND("surface", "mesh a parametric surface (paper §5-6): --list, --surface NAME --h H, or CONFIG.json",
              ablmg::cli::runSurface)
