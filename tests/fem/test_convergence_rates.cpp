// Verification: a smooth manufactured solution converges at the optimal
// P1 rates on ≥ 4 levels of uniform and of randomly perturbed ("unstructured") meshes.
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::fem;

namespace {
/// Least-squares slope of log(e) against log(h).
double fittedSlope(const std::vector<double>& h, const std::vector<double>& e) {
  const int n = int(h.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

struct Rates {
  double l2, h1;
};

Rates measureRates(const std::string& problem, double perturbation) {
  const TestProblem tp = makeProblem(problem);
  std::vector<double> h, l2, h1;
  for (int n : {8, 16, 32, 64, 128}) {
    const Mesh2 m = unitSquareMesh(n, perturbation, 1000 + n);
    const PoissonSolution s = solvePoisson(m, tp.poisson());
    const ErrorReport e = computeErrors(m, s.u, tp.exact());
    h.push_back(1.0 / n);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
    if (l2.size() > 1) {  // monotone decrease at every level
      EXPECT_LT(l2.back(), l2[l2.size() - 2]);
      EXPECT_LT(h1.back(), h1[h1.size() - 2]);
    }
  }
  return {fittedSlope(h, l2), fittedSlope(h, h1)};
}
}  // namespace

TEST(ConvergenceRates, SmoothSolutionUniformMeshes) {
  const Rates r = measureRates("smooth", 0.0);
  EXPECT_NEAR(r.l2, 2.0, 0.15);
  EXPECT_NEAR(r.h1, 1.0, 0.1);
}

TEST(ConvergenceRates, SmoothSolutionPerturbedMeshes) {
  const Rates r = measureRates("smooth", 0.2);
  EXPECT_NEAR(r.l2, 2.0, 0.15);
  EXPECT_NEAR(r.h1, 1.0, 0.1);
}

TEST(ConvergenceRates, SineSolutionPerturbedMeshes) {
  const Rates r = measureRates("sine", 0.2);
  EXPECT_NEAR(r.l2, 2.0, 0.15);
  EXPECT_NEAR(r.h1, 1.0, 0.1);
}

TEST(ConvergenceRates, InterpolantErrorIsBelowFiniteElementErrorInH1Sense) {
  // Céa: |u − u_h|_H1 ≤ |u − I_h u|_H1; and in L2 both are O(h²) of the same size.
  const TestProblem tp = makeProblem("smooth");
  const Mesh2 m = unitSquareMesh(32, 0.2, 9);
  const PoissonSolution s = solvePoisson(m, tp.poisson());
  const ErrorReport fe = computeErrors(m, s.u, tp.exact());
  const ErrorReport in = computeErrors(m, interpolate(m, tp.u), tp.exact());
  EXPECT_LE(fe.h1, in.h1 * (1 + 1e-12));
  EXPECT_NEAR(fe.l2Interp, in.l2, 1e-14);
  EXPECT_LT(fe.l2, 3 * in.l2);
  EXPECT_GT(fe.l2, in.l2 / 3);
}

TEST(ConvergenceRates, MixedDirichletNeumannPerturbedMeshes) {
  // smooth u = eˣ sin(πy) + xy; Neumann flux ∂u/∂n on the right (n = +x) and top (n = +y).
  const TestProblem tp = makeProblem("smooth");
  PoissonProblem p;
  p.f = tp.f;
  p.dirichlet[1] = tp.u;
  p.dirichlet[4] = tp.u;
  p.neumann[2] = ScalarFn([&](double x, double y) { return tp.grad(x, y).x(); });
  p.neumann[3] = ScalarFn([&](double x, double y) { return tp.grad(x, y).y(); });
  std::vector<double> h, l2, h1;
  for (int n : {8, 16, 32, 64, 128}) {
    const Mesh2 m = unitSquareMesh(n, 0.2, 77 + n);
    const ErrorReport e = computeErrors(m, solvePoisson(m, p).u, tp.exact());
    h.push_back(1.0 / n);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
  }
  EXPECT_NEAR(fittedSlope(h, l2), 2.0, 0.15);
  EXPECT_NEAR(fittedSlope(h, h1), 1.0, 0.1);
}

TEST(ConvergenceRates, ReentrantCornerIsLimitedByItsSingularity) {
  // u = r^(2/3) sin(2θ/3) ∈ H^(5/3−ε): uniform refinement gives h^(2/3) in H1 and h^(4/3) in L2
  // (the motivation for adaptive meshes; the adaptive loop is compared against these slopes).
  const TestProblem tp = makeProblem("lshape");
  std::vector<double> h, l2, h1;
  for (int n : {8, 16, 32, 64, 128}) {
    const Mesh2 m = structuredMesh(tp.domain, n, n);  // n cells over the length 2 of the box
    const ErrorReport e = computeErrors(m, solvePoisson(m, tp.poisson()).u, tp.exact());
    h.push_back(2.0 / n);
    l2.push_back(e.l2);
    h1.push_back(e.h1);
  }
  EXPECT_NEAR(fittedSlope(h, h1), 2.0 / 3, 0.08);
  EXPECT_NEAR(fittedSlope(h, l2), 4.0 / 3, 0.12);
}
