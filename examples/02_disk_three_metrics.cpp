//                 ablmg example 02: the radius-10 disk with the paper's three metrics
//
// Sample runs:
//   ex02_disk_three_metrics                        (all three, the paper's sizes, ≈ 4000 nodes each)
//   ex02_disk_three_metrics --case ring            (one of: constant, ring, line, all)
//   ex02_disk_three_metrics --scale 3 --out small  (the CTest run: sizes × 3, ≈ 9× fewer nodes)
//
// Description:
//   The examples of the paper's §4.3 (Figs. 13–14): the disk of radius 10 centred at the
//   origin, meshed for three metrics given by sizes (h1, h2) and the angle θ of h1's direction
//   (eq. 2):
//     constant  h1 = 0.5, h2 = 0.2, θ = π/4                       (paper: q mean 0.9253)
//     ring      h1 = 0.15 |√(x²+y²) − 6| + 0.2, h2 = h1/2, θ = 0   (paper: q mean 0.9119)
//     line      h1 = 0.1 |y| + 0.2, h2 = h1/2, θ = 0               (paper: q mean 0.9727)
//   The ring metric refines towards the circle r = 6, the line metric towards y = 0.
//   `--scale s` multiplies every size by s (s = 1: the paper's metrics).
//
//   For each metric:
//     1. the disk as a smooth boundary loop (Domain::disk: 2048 points on the circle; the
//        mesher places its own boundary nodes along it),
//     2. the metric as muparser expressions (core/metric_field.hpp),
//     3. mesher::meshDomain (bubbles §3, ABLMG §4),
//     4. one `Case` line: nodes, triangles, element quality q (mean/min/max) with the paper's
//        mean, and the share of edges of metric length in [1/√2, √2] and within 10 % of 1,
//     5. OUT_<case>_bubbles.png (the packed ellipses, Fig. 13), OUT_<case>_mesh.png (Fig. 14,
//        triangles coloured by q) and OUT_<case>.vtu.
//   Exit status 1 if a mesh is invalid or the options are bad.
#include "ablmg/core/error.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace ablmg;

namespace {

struct Options {
  std::string which = "all";      ///< constant, ring, line or all
  double scale = 1;               ///< multiplies h1 and h2
  std::string out = "ex02_disk";  ///< output prefix
  std::uint64_t seed = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  const char* usage = "options: --case constant|ring|line|all, --scale S, --out PREFIX, --seed N";
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(i + 1 < argc, key << " needs a value (" << usage << ")");
    const std::string value = argv[++i];
    if (key == "--case")
      o.which = value;
    else if (key == "--scale")
      o.scale = std::stod(value);
    else if (key == "--out")
      o.out = value;
    else if (key == "--seed")
      o.seed = std::stoull(value);
    else
      ABLMG_REQUIRE(false, "unknown option " << key << " (" << usage << ")");
  }
  ABLMG_REQUIRE(o.which == "constant" || o.which == "ring" || o.which == "line" || o.which == "all",
                "--case must be constant, ring, line or all, got '" << o.which << "'");
  ABLMG_REQUIRE(std::isfinite(o.scale) && o.scale >= 0.2 && o.scale <= 20,
                "--scale must be in [0.2, 20], got " << o.scale);
  return o;
}

struct Case {
  const char* name;
  std::string h1, h2, theta;  ///< muparser expressions in x, y (sizes before scaling)
  double paperMeanQuality;
};

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  std::printf("Options: --case %s --scale %g --out %s --seed %llu\n", opt.which.c_str(), opt.scale, opt.out.c_str(),
              (unsigned long long)opt.seed);
  const std::vector<Case> cases = {
      {"constant", "0.5", "0.2", "pi/4", 0.9253},
      {"ring", "0.15*abs(sqrt(x^2+y^2)-6)+0.2", "0.5*(0.15*abs(sqrt(x^2+y^2)-6)+0.2)", "0", 0.9119},
      {"line", "0.1*abs(y)+0.2", "0.5*(0.1*abs(y)+0.2)", "0", 0.9727},
  };

  // 1. The disk of radius 10, one smooth loop with tag 1.
  const Domain disk = Domain::disk({0, 0}, 10);
  bool allValid = true;
  for (const Case& c : cases) {
    if (opt.which != "all" && opt.which != c.name) continue;
    // 2. The metric (sizes form, eq. 2), scaled.
    const std::string s = std::to_string(opt.scale) + "*";
    const AnalyticMetricField metric(AnalyticMetricField::Form::Sizes, s + "(" + c.h1 + ")", s + "(" + c.h2 + ")",
                                     c.theta, std::string("case ") + c.name);
    // 3. Mesh.
    mesher::MeshOptions options;
    options.placement.seed = opt.seed;
    const mesher::MeshResult r = mesher::meshDomain(disk, metric, options);
    // 4. Measure.
    const mesher::MeshQuality q = mesher::meshQuality(r.mesh, r.metric);
    const auto& ps = r.stats.placement;
    const double seconds = ps.secondsInitial + ps.secondsDynamics + ps.secondsAdjacency + ps.secondsPopulation +
                           r.stats.connect.secondsLocalMeshes + r.stats.connect.secondsRepair;
    std::printf(
        "Case %-8s N = %5ld  E = %5ld  q mean %.3f (paper %.4f) min %.3f max %.3f  "
        "l in [1/sqrt2, sqrt2] %.1f %%  |l-1| <= 0.1 %.1f %%  valid %s  %d steps %.1f s\n",
        c.name, q.vertices, q.triangles, q.elements.mean, c.paperMeanQuality, q.elements.min, q.elements.max,
        100 * q.edgeLengths.inSqrt2, 100 * q.edgeLengths.within10, q.valid ? "yes" : "no", ps.steps, seconds);
    allValid = allValid && q.valid;
    // 5. Pictures and the .vtu (metric as point data: m11 m12 m22, h1, h2, angle).
    const std::string prefix = opt.out + "_" + c.name;
    io::drawBubbles(prefix + "_bubbles.png", disk, r.mesh.vertices, r.metric);
    io::drawMesh(prefix + "_mesh.png", r.mesh, mesher::elementQualities(r.mesh, r.metric), "q");
    io::writeVtu(prefix + ".vtu", r.mesh, io::metricFields(r.metric));
    std::printf("  wrote %s_bubbles.png, %s_mesh.png, %s.vtu\n", prefix.c_str(), prefix.c_str(), prefix.c_str());
  }
  std::printf("All valid: %s\n", allValid ? "yes" : "no");
  return allValid ? 0 : 1;
} catch (const std::exception& e) {
  std::cerr << "ex02_disk_three_metrics: " << e.what() << "\n";
  return 1;
}
