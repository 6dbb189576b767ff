// ablmg surface --surface NAME --h H -o OUT.mesh [--vtu OUT.vtu] [--stl OUT.stl]
//               [--png-param OUT.png] [--json R.json] [--seed N]
// ablmg surface --list
//
// Parametric surface triangulation by the mapping method (paper §5–6): the parameter domain
// of a built-in surface is meshed with the induced metric M2 = Jᵀ M3 J (eq. 16) of the
// isotropic 3D size h (eq. 17), the mesh is mapped back to 3D and written; the report gives
// Lee's quality α (eqs. 19–20, Table 2 bins) and the 3D edge lengths relative to h.
// Errors are exceptions (one line, exit 1); outputs are written only once the mesh exists.
#include "cli/command.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/medit.hpp"
#include "io/picture.hpp"
#include "io/stl.hpp"
#include "io/vtu.hpp"
#include "mesher/mesher.hpp"
#include "mesher/quality.hpp"
#include "mesher/surface.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace ablmg::cli {
namespace {

const char* kHelp = R"(usage: ablmg surface --surface NAME --h H -o OUT.mesh [--vtu OUT.vtu] [--stl OUT.stl]
                     [--png-param OUT.png] [--json R.json] [--seed N]
       ablmg surface --list

Meshes a parametric surface r(u,v) by the mapping method (paper §5–6): the (u,v) domain is
meshed with M2 = J^T M3 J (eq. 16) for the isotropic 3D size H (eq. 17), then mapped to 3D.
  --surface NAME   a built-in surface (--list shows them with formulas and (u,v) domains)
  --h H            target 3D edge length (> 0)
  -o OUT.mesh      medit surface mesh (Dimension 3)
  --vtu, --stl     3D .vtu (Lee's quality as cell data) and STL outputs
  --png-param PNG  the parameter-space mesh coloured by Lee's quality
  --json R.json    report: counts, quality distribution, edge lengths, manifold check, times
  --seed N         placement seed (default 1)
)";

double parsePositive(const std::string& v, const std::string& what) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(v, &used);
  } catch (...) {
    used = 0;
  }
  ABLMG_REQUIRE(used == v.size() && std::isfinite(x) && x > 0, what << ": expected a positive number, got '" << v << "'");
  return x;
}

int runSurface(const std::vector<std::string>& args) {
  std::string name, meshPath, vtuPath, stlPath, pngPath, jsonPath;
  double h = 0;
  long long seed = 1;
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
      h = parsePositive(value(), "surface: --h");
    } else if (a == "-o") {
      meshPath = value();
    } else if (a == "--vtu") {
      vtuPath = value();
    } else if (a == "--stl") {
      stlPath = value();
    } else if (a == "--png-param") {
      pngPath = value();
    } else if (a == "--json") {
      jsonPath = value();
    } else if (a == "--seed") {
      seed = std::llround(parsePositive(value(), "surface: --seed"));
    } else {
      ABLMG_REQUIRE(false, "surface: unknown argument '" << a << "' (see ablmg surface --help)");
    }
  }
  ABLMG_REQUIRE(!name.empty(), "surface: --surface NAME is required (ablmg surface --list)");
  ABLMG_REQUIRE(h > 0, "surface: --h H is required");
  ABLMG_REQUIRE(!meshPath.empty() || !vtuPath.empty() || !stlPath.empty() || !jsonPath.empty(),
                "surface: no output (give -o OUT.mesh, --vtu, --stl or --json)");

  const auto surface = mesher::makeBuiltinSurface(name);
  const mesher::Metric3Field m3 = mesher::isotropicMetric3(h);
  const mesher::InducedMetricField m2(*surface, m3);
  mesher::MeshOptions options;
  options.placement.seed = std::uint64_t(seed);
  const auto t0 = std::chrono::steady_clock::now();
  const mesher::MeshResult r = mesher::meshDomain(surface->parameterDomain(), m2, options);
  const mesher::SurfaceMesh s = mesher::mapToSurface(r.mesh, *surface);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const mesher::MeshQuality q = mesher::surfaceQuality(s, m3);
  ABLMG_REQUIRE(q.valid, "surface: the 3D mesh is not a consistently oriented manifold: " << q.firstProblem);
  const std::vector<double> alpha = mesher::leeQuality(s, m3);

  std::vector<std::string> written;
  try {
    if (!meshPath.empty()) { io::writeSurfaceMesh(meshPath, s.vertices, s.triangles); written.push_back(meshPath); }
    if (!vtuPath.empty()) {
      io::writeVtu(vtuPath, s.vertices, s.triangles, {}, {io::Field{"lee_quality", 1, alpha}});
      written.push_back(vtuPath);
    }
    if (!stlPath.empty()) { io::writeStl(stlPath, s.vertices, s.triangles, name); written.push_back(stlPath); }
    if (!pngPath.empty()) { io::drawMesh(pngPath, r.mesh, alpha, "Lee quality"); written.push_back(pngPath); }
    if (!jsonPath.empty()) {
      nlohmann::json j = {{"surface", name}, {"description", surface->description()}, {"h", h},
                          {"seconds", seconds}, {"quality", mesher::toJson(q)}, {"outputs", written}};
      io::writeFileAtomically(jsonPath, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
      written.push_back(jsonPath);
    }
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    throw;
  }
  std::cout << "ablmg surface: " << name << ", h = " << h << ": " << q.vertices << " vertices, " << q.triangles
            << " triangles in " << seconds << " s; manifold: yes\n"
            << mesher::toText(q);
  for (const auto& w : written) std::cout << "  -> " << w << "\n";
  return 0;
}

} // namespace
} // namespace ablmg::cli

ABLMG_COMMAND("surface", "mesh a built-in parametric surface (paper §5-6): --list, --surface NAME --h H",
              ablmg::cli::runSurface)
