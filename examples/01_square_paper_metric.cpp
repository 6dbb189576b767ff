//                 ablmg example 01: the paper's square with the metric of eq. (4)
//
// Sample runs:
//   ex01_square_paper_metric                      (h = 0.3: ≈ 2300 nodes, the paper's §4.3 size)
//   ex01_square_paper_metric --h 0.15             (≈ 4× the nodes)
//   ex01_square_paper_metric --h 0.6 --out small  (the CTest run; writes small.mesh, ...)
//
// Description:
//   Meshes the square [-3, 3]² with the anisotropic Riemannian metric of the paper's eq. (4),
//
//       M(x, y) = 1/h² · [ 1 + 4x²   4xy    ]
//                        [ 4xy       1 + 4y² ],
//
//   i.e. M = (I + 4 p pᵀ)/h² with p = (x, y): the size is h along circles around the origin
//   and h / sqrt(1 + 4r²) along the radius, so elements flatten radially away from the centre
//   (the Hessian metric of z = x² + y², made to measure the surface's arc length).
//   The paper (§4.3, Fig. 12) reports 2301 nodes and 4525 elements with element quality
//   mean 0.969, min 0.716, max 0.999; it does not state h. h = 0.3 gives about that many
//   nodes: N ≈ (2/√3) ∫ √det M dA ≈ 2180 interior + boundary.
//
//   The steps are those of any use of the mesher:
//     1. the domain (core/domain.hpp) and the metric field (core/metric_field.hpp),
//     2. mesher::meshDomain — bubble placement (§3) and the ABLMG connection (§4),
//     3. quality in the metric (mesher/quality.hpp): edge lengths l (target 1, eq. 13) and
//        element quality q (Borouchaki et al.),
//     4. the files: OUT.mesh (+ OUT.sol, the metric per vertex, for `ablmg stats`), OUT.vtu,
//        OUT_mesh.png (triangles coloured by q) and OUT_bubbles.png (the packed ellipses).
//   Exit status 1 if the mesh is not valid or the options are bad.
#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

using namespace ablmg;

namespace {

struct Options {
  double h = 0.3;                   ///< the h of eq. (4)
  std::string out = "ex01_square";  ///< output prefix
  std::uint64_t seed = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(i + 1 < argc, key << " needs a value (options: --h H, --out PREFIX, --seed N)");
    const std::string value = argv[++i];
    if (key == "--h")
      o.h = std::stod(value);
    else if (key == "--out")
      o.out = value;
    else if (key == "--seed")
      o.seed = std::stoull(value);
    else
      ABLMG_REQUIRE(false, "unknown option " << key << " (options: --h H, --out PREFIX, --seed N)");
  }
  ABLMG_REQUIRE(std::isfinite(o.h) && o.h > 0.01 && o.h <= 3, "--h must be in (0.01, 3], got " << o.h);
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  std::printf("Options: --h %g --out %s --seed %llu\n", opt.h, opt.out.c_str(), (unsigned long long)opt.seed);

  // 1. The square [-3, 3]² (tags 1..4 bottom, right, top, left) and the metric of eq. (4),
  //    given as tensor components m11, m12, m22 (muparser expressions in x, y).
  const Domain square = Domain::rectangle(-3, -3, 3, 3);
  char invH2[64];
  std::snprintf(invH2, sizeof invH2, "/%.17g^2", opt.h);
  const AnalyticMetricField metric(AnalyticMetricField::Form::Tensor, "(1+4*x^2)" + std::string(invH2),
                                   "4*x*y" + std::string(invH2), "(1+4*y^2)" + std::string(invH2), "eq. (4)");

  // 2. Bubble placement and ABLMG connection. The result is valid or meshDomain throws.
  mesher::MeshOptions options;
  options.placement.seed = opt.seed;
  const mesher::MeshResult r = mesher::meshDomain(square, metric, options);
  const auto& ps = r.stats.placement;
  const auto& cs = r.stats.connect;
  std::printf("Placement: %ld nodes (predicted %ld), %d steps, %.2f s\n", ps.finalNodes, ps.predictedNodes, ps.steps,
              ps.secondsInitial + ps.secondsDynamics + ps.secondsAdjacency + ps.secondsPopulation);
  std::printf(
      "Connection: %ld intersection tests, %ld crossings, %ld edges deleted by eq. (12), %ld repaired triangles\n",
      cs.intersectionTests, cs.crossingsFound, cs.deletedEdges, cs.repairedTriangles);

  // 3. Quality in the metric the mesh was built for.
  const mesher::MeshQuality q = mesher::meshQuality(r.mesh, r.metric);
  std::cout << mesher::toText(q);
  std::printf("Mesh: N = %ld nodes, E = %ld triangles (paper: 2301, 4525)\n", q.vertices, q.triangles);
  std::printf("Element quality q: mean %.3f min %.3f max %.3f (paper: 0.969, 0.716, 0.999)\n", q.elements.mean,
              q.elements.min, q.elements.max);
  std::printf("Edges with metric length in [1/sqrt2, sqrt2]: %.1f %%, within 10 %% of 1: %.1f %%\n",
              100 * q.edgeLengths.inSqrt2, 100 * q.edgeLengths.within10);

  // 4. Files.
  io::writeMesh(opt.out + ".mesh", r.mesh);
  io::writeSol(opt.out + ".sol", r.metric);
  io::writeVtu(opt.out + ".vtu", r.mesh, io::metricFields(r.metric));
  const std::vector<double> quality = mesher::elementQualities(r.mesh, r.metric);
  io::drawMesh(opt.out + "_mesh.png", r.mesh, quality, "q");
  io::drawBubbles(opt.out + "_bubbles.png", square, r.mesh.vertices, r.metric);
  std::printf("Wrote %s.mesh, %s.sol, %s.vtu, %s_mesh.png, %s_bubbles.png\n", opt.out.c_str(), opt.out.c_str(),
              opt.out.c_str(), opt.out.c_str(), opt.out.c_str());
  std::printf("Valid: %s\n", q.valid ? "yes" : "no");
  return q.valid ? 0 : 1;
} catch (const std::exception& e) {
  std::cerr << "ex01_square_paper_metric: " << e.what() << "\n";
  return 1;
}
