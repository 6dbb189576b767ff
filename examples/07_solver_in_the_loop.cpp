//                 ablmg example 07: your solver in the loop, cycle by cycle
//
// Sample runs:
//   ex07_solver_in_the_loop                          (6 cycles, 500 → 16000 vertices, pictures)
//   ex07_solver_in_the_loop --cycles 8 --n0 1000     (up to 128k vertices)
//   ex07_solver_in_the_loop --contrast 1000          (a sharper coefficient jump)
//   ex07_solver_in_the_loop --cycles 3 --pictures 0  (the CTest run)
//
// Description:
//   The adaptive loop driven step by step, the way a solver that owns its own discretisation
//   uses ablmg (as MMG users call mmg2d between solves): nothing here needs an exact solution.
//   The problem is a diffusion whose coefficient jumps across a circle,
//       −∇·(κ ∇u) = 1 in (0,1)²,  u = 0 on the boundary,
//       κ = 1 inside |x − (0.5, 0.5)| < 0.3 and `contrast` (default 100) outside, joined by a
//       tanh layer of width `width` (default 0.01),
//   so the solution bends sharply in a thin ring (∇u drops by the factor κ across it) and is
//   100× more curved inside the disk than outside: the loop puts most vertices inside and
//   makes elements thin across the ring, long along it.
//   Each cycle
//     1. solves on the current mesh ("your solver": here fem::solvePoisson, CHOLMOD),
//     2. recovers the Hessian of u_h at the vertices (adapt::recoverHessians),
//     3. estimates the P1 interpolation error from it (adapt::estimateInterpolationError: the
//        error figure of a loop without an exact solution, exact for quadratics),
//     4. builds the Lp-optimal metric for the next vertex count (adapt::metricFromRecovered)
//        and remeshes the same domain in it (adapt::remesh: bubble placement + ABLMG),
//   and prints the vertices, the estimate and the solution's maximum (which converges). The
//   estimate should fall like N⁻¹ (optimal P1; measured −1.06 over 1k–32k vertices with 7
//   cycles), the rate printed at the end; exit status 1 if it falls slower than N^-0.8 over the
//   adapted cycles. (With a true jump, --width 1e-9, the kink cuts through elements that do
//   not follow the circle exactly and the estimate falls irregularly, about N^-0.7.) Writes
//   ex07_mesh_K.png (mesh coloured by the estimated error per triangle) for the first and last
//   cycles unless --pictures 0.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/convergence.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/io/picture.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

using namespace ablmg;

namespace {

struct Options {
  int cycles = 6;
  double n0 = 500;        ///< vertices of the first (uniform) mesh
  double contrast = 100;  ///< κ outside the disk
  double width = 0.01;    ///< width of κ's transition layer
  bool pictures = true;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(i + 1 < argc, key << " needs a value");
    const double v = std::atof(argv[++i]);
    if (key == "--cycles")
      o.cycles = int(v);
    else if (key == "--n0")
      o.n0 = v;
    else if (key == "--contrast")
      o.contrast = v;
    else if (key == "--width")
      o.width = v;
    else if (key == "--pictures")
      o.pictures = v != 0;
    else
      ABLMG_REQUIRE(false, "unknown option " << key << " (valid: --cycles --n0 --contrast --width --pictures)");
  }
  ABLMG_REQUIRE(o.cycles >= 3 && o.n0 >= 10 && o.contrast > 0 && o.width > 0,
                "need --cycles >= 3, --n0 >= 10, --contrast > 0, --width > 0");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);

    // Step 1: the domain and the PDE data. κ and f are plain functions of (x, y); the
    // boundary tags of Domain::rectangle are 1–4, all Dirichlet here.
    const Domain domain = Domain::rectangle(0, 0, 1, 1);
    fem::PoissonProblem pde;
    const double contrast = o.contrast;
    const double width = o.width;
    pde.kappa = [contrast, width](double x, double y) {
      const double r = std::hypot(x - 0.5, y - 0.5);
      return 1 + (contrast - 1) * 0.5 * (1 + std::tanh((r - 0.3) / width));
    };
    pde.f = 1.0;
    pde.setDirichletEverywhere(0.0);
    pde.threadSafeFunctions = true;  // pure lambdas: assembly may run in parallel

    // Step 2: the loop's settings (schedule, Lp norm, mesher options) and the first mesh,
    // uniform and isotropic with about n0 vertices.
    adapt::AdaptOptions options;
    options.metric.p = 2;
    mesher::MeshResult current = adapt::uniformMesh(domain, o.n0, options.mesh);

    std::vector<double> vertices, estimates;
    for (int k = 0; k < o.cycles; ++k) {
      // Step 3: solve on the current mesh. A solver of your own would go here; all the loop
      // needs back is u_h at the mesh vertices.
      const fem::PoissonSolution sol = fem::solvePoisson(current.mesh, pde);
      const std::span<const double> u(sol.u.data(), std::size_t(sol.u.size()));

      // Step 4: recovered Hessians → the error estimate of this mesh.
      const auto hessians = adapt::recoverHessians(current.mesh, u, options.hessian);
      const auto estimate = adapt::estimateInterpolationError(current.mesh, hessians);
      vertices.push_back(double(current.mesh.numVertices()));
      estimates.push_back(estimate.l2);
      std::printf("Cycle %d: N=%d T=%d  estimated |u - I_h u|_L2 = %.3e  max u_h = %.6f  q min %.2f\n", k,
                  current.mesh.numVertices(), current.mesh.numTriangles(), estimate.l2, sol.u.maxCoeff(),
                  adapt::metricQuality(current.mesh, current.metric).min);
      std::fflush(stdout);
      if (o.pictures && (k == 0 || k + 1 == o.cycles))
        io::drawMesh("ex07_mesh_" + std::to_string(k) + ".png", current.mesh, estimate.elementL2, "estimated error");
      if (k + 1 == o.cycles) break;

      // Step 5: the metric for twice the vertices, and the new mesh of the same domain in it
      // (the metric is interpolated from the current mesh; the result is a valid mesh or an
      // exception). A solver that has a mesh but no Domain calls adapt::remesh(mesh, metric,
      // RemeshOptions) instead (adapt/remesh.hpp): the domain is the mesh's boundary, and the
      // call clamps to [hmin, hmax] and grades as `ablmg remesh` does.
      const double next = o.n0 * std::pow(2.0, k + 1);
      std::vector<Metric2> metric = adapt::metricFromRecovered(current.mesh, hessians, next, options).metric;
      current = adapt::remesh(domain, current.mesh, std::move(metric), options.mesh);
    }

    // Step 6: the estimate's rate over the adapted cycles (cycle 0 is uniform).
    const std::vector<double> n(vertices.begin() + 1, vertices.end()), e(estimates.begin() + 1, estimates.end());
    const double rate = adapt::logLogSlope(n, e);
    std::printf("Estimated-error rate over cycles 1-%d: %.3f (optimal P1: -1)\n", o.cycles - 1, rate);
    std::printf("Falls at least like N^-0.8: %s\n", rate < -0.8 ? "yes" : "NO");
    return rate < -0.8 ? 0 : 1;
  } catch (const ablmg::Error& e) {
    std::cerr << "ex07_solver_in_the_loop: " << e.what() << "\n";
    return 1;
  }
}
