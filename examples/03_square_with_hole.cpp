//                 ablmg example 03: a domain with holes and a graded boundary-layer metric
//
// Sample runs:
//   ex03_square_with_hole                          (≈ 1100 nodes)
//   ex03_square_with_hole --scale 0.5              (sizes halved: ≈ 4× the nodes)
//   ex03_square_with_hole --scale 2 --out small    (the CTest run)
//
// Description:
//   A domain with several boundary loops (core/domain.hpp): the square [-1, 1]² (tags 1–4)
//   with two holes — a circle of radius R = 0.35 at the origin, given as a smooth loop of
//   256 points (tag 5; the mesher places its own nodes along it), and a small square
//   [0.55, 0.8]² (tag 6; its 4 corners are mesh vertices). Holes may be given in either
//   orientation; the Domain constructor orients them and validate() rejects crossing loops.
//
//   The metric is written in C++ as a MetricField subclass (instead of muparser strings):
//   a boundary layer around the circle, graded with the distance d = r − R,
//       normal (radial) size   h_n = min(s·(0.008 + 0.25 d), s·0.08)
//       tangential size        h_t = min(s·(0.04  + 0.15 d), s·0.08)
//   so elements at the circle are 5 : 1 and flattened towards it, and the mesh becomes
//   isotropic (size 0.08·s) about 0.3 away. s = --scale. The small square hole sits in the
//   isotropic part and only shows that its corners and tags are kept.
//
//   Steps: 1. the loops, 2. the metric, 3. mesher::meshDomain, 4. quality and the number of
//   boundary edges per tag, 5. OUT.mesh (+ OUT.sol), OUT.vtu, OUT_mesh.png, OUT_bubbles.png.
//   Exit status 1 if the mesh is invalid or a tag is missing on the boundary.
#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numbers>
#include <string>

using namespace ablmg;

namespace {

constexpr double kHoleRadius = 0.35;

/// The boundary-layer metric of the description: h_t along the circle, h_n across it.
class HoleLayerMetric final : public MetricField {
 public:
  explicit HoleLayerMetric(double scale) : s_(scale) {}
  Metric2 at(const Vec2& p) const override {
    const double r = p.norm();
    const double d = std::max(r - kHoleRadius, 0.0);
    const double hn = s_ * std::min(0.008 + 0.25 * d, 0.08);
    const double ht = s_ * std::min(0.04 + 0.15 * d, 0.08);
    // h1 = h_t along the tangent (angle of the radius + π/2), h2 = h_n along the radius.
    const double tangent = std::atan2(p.y(), p.x()) + 0.5 * std::numbers::pi;
    return Metric2::fromSizes(ht, hn, tangent);
  }

 private:
  double s_;
};

struct Options {
  double scale = 1;
  std::string out = "ex03_holes";
  std::uint64_t seed = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(i + 1 < argc, key << " needs a value (options: --scale S, --out PREFIX, --seed N)");
    const std::string value = argv[++i];
    if (key == "--scale")
      o.scale = std::stod(value);
    else if (key == "--out")
      o.out = value;
    else if (key == "--seed")
      o.seed = std::stoull(value);
    else
      ABLMG_REQUIRE(false, "unknown option " << key << " (options: --scale S, --out PREFIX, --seed N)");
  }
  ABLMG_REQUIRE(std::isfinite(o.scale) && o.scale >= 0.1 && o.scale <= 4,
                "--scale must be in [0.1, 4], got " << o.scale);
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  std::printf("Options: --scale %g --out %s --seed %llu\n", opt.scale, opt.out.c_str(), (unsigned long long)opt.seed);

  // 1. Loops: outer square (counter-clockwise, one tag per segment), circle, square hole.
  const BoundaryLoop outer = BoundaryLoop::polygon({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, {1, 2, 3, 4});
  BoundaryLoop circle;
  const int samples = 256;
  for (int k = 0; k < samples; ++k) {
    const double t = 2 * std::numbers::pi * k / samples;
    circle.points.push_back({kHoleRadius * std::cos(t), kHoleRadius * std::sin(t)});
  }
  circle.tags.assign(samples, 5);
  circle.smooth = true;
  const BoundaryLoop box = BoundaryLoop::polygon({{0.55, 0.55}, {0.8, 0.55}, {0.8, 0.8}, {0.55, 0.8}}, {6, 6, 6, 6});
  const Domain domain(outer, {circle, box});
  std::printf("Domain: %zu loops, area %.6f (exact %.6f for the 256-gon)\n", domain.loops().size(), domain.area(),
              4 - 0.5 * samples * kHoleRadius * kHoleRadius * std::sin(2 * std::numbers::pi / samples) - 0.0625);

  // 2.–3. Metric and mesh.
  const HoleLayerMetric metric(opt.scale);
  mesher::MeshOptions options;
  options.placement.seed = opt.seed;
  const mesher::MeshResult r = mesher::meshDomain(domain, metric, options);

  const auto& ps = r.stats.placement;
  std::printf("Placement: %ld nodes (predicted %ld), %d steps, %.2f s\n", ps.finalNodes, ps.predictedNodes, ps.steps,
              ps.secondsInitial + ps.secondsDynamics + ps.secondsAdjacency + ps.secondsPopulation);

  // 4. Quality, and the tags the boundary edges carry.
  const mesher::MeshQuality q = mesher::meshQuality(r.mesh, r.metric);
  std::cout << mesher::toText(q);
  std::map<int, int> edgesPerTag;
  for (const auto& e : r.mesh.boundaryEdges) ++edgesPerTag[e.ref];
  std::printf("Boundary edges per tag:");
  for (const auto& [tag, count] : edgesPerTag) std::printf("  %d: %d", tag, count);
  std::printf("\n");
  const bool allTags = edgesPerTag.size() == 6;
  std::printf("Mesh: N = %ld nodes, E = %ld triangles, q mean %.3f min %.3f, l in [1/sqrt2, sqrt2] %.1f %%\n",
              q.vertices, q.triangles, q.elements.mean, q.elements.min, 100 * q.edgeLengths.inSqrt2);

  // 5. Files.
  io::writeMesh(opt.out + ".mesh", r.mesh);
  io::writeSol(opt.out + ".sol", r.metric);
  io::writeVtu(opt.out + ".vtu", r.mesh, io::metricFields(r.metric));
  io::drawMesh(opt.out + "_mesh.png", r.mesh, mesher::elementQualities(r.mesh, r.metric), "q");
  io::drawBubbles(opt.out + "_bubbles.png", domain, r.mesh.vertices, r.metric);
  std::printf("Wrote %s.mesh, %s.sol, %s.vtu, %s_mesh.png, %s_bubbles.png\n", opt.out.c_str(), opt.out.c_str(),
              opt.out.c_str(), opt.out.c_str(), opt.out.c_str());
  std::printf("Valid: %s, all 6 tags on the boundary: %s\n", q.valid ? "yes" : "no", allTags ? "yes" : "no");
  return q.valid && allTags ? 0 : 1;
} catch (const std::exception& e) {
  std::cerr << "ex03_square_with_hole: " << e.what() << "\n";
  return 1;
}
