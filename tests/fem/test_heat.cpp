// Mirrors fem/heat.hpp: temporal convergence orders 1 (backward Euler) and 2 (BDF2) on a
// manufactured solution that P1 represents exactly in space (so only the time error is left),
// one factorisation per distinct Δt, the diffusion really acting (a decaying sine mode), bad
// steps refused. Also the transient problems' f = u_t − κΔu against finite differences.
#include "ablmg/fem/heat.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace ablmg;
using namespace ablmg::fem;

namespace {

/// u = (1 + x + 2y) sin(2t) + x/2: linear in space, so P1 holds it exactly; Δu = 0, f = u_t.
double uExact(double x, double y, double t) { return (1 + x + 2 * y) * std::sin(2 * t) + 0.5 * x; }

double errorAtEnd(TimeScheme scheme, int steps) {
  static const Mesh2 mesh = unitSquareMesh(8, 0.1, 4);
  HeatProblem p;
  p.kappa = 0.7;
  p.dirichlet = uExact;
  p.f = [](double x, double y, double t) { return 2 * (1 + x + 2 * y) * std::cos(2 * t); };
  HeatSolver solver(mesh, p, scheme);
  Eigen::VectorXd u0(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) u0[v] = uExact(mesh.vertices[v].x(), mesh.vertices[v].y(), 0);
  solver.setState(0, u0);
  const double dt = 1.0 / steps;
  for (int n = 0; n < steps; ++n) solver.step(dt);
  EXPECT_NEAR(solver.time(), 1.0, 1e-12);
  EXPECT_EQ(solver.factorizations(), scheme == TimeScheme::BDF2 ? 2 : 1);
  return computeErrors(mesh, solver.u(), {[](double x, double y) { return uExact(x, y, 1.0); }, {}, true}, 5).l2;
}

}  // namespace

TEST(Heat, BackwardEulerIsFirstOrderInTime) {
  const double e1 = errorAtEnd(TimeScheme::BackwardEuler, 20), e2 = errorAtEnd(TimeScheme::BackwardEuler, 40),
               e3 = errorAtEnd(TimeScheme::BackwardEuler, 80);
  EXPECT_NEAR(std::log2(e1 / e2), 1.0, 0.1);
  EXPECT_NEAR(std::log2(e2 / e3), 1.0, 0.05);
}

TEST(Heat, Bdf2IsSecondOrderInTime) {
  // (the first step is backward Euler: its O(Δt²) local error keeps the global order 2)
  const double e1 = errorAtEnd(TimeScheme::BDF2, 40), e2 = errorAtEnd(TimeScheme::BDF2, 80),
               e3 = errorAtEnd(TimeScheme::BDF2, 160);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.15);
  EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.06);
  EXPECT_LT(e2, errorAtEnd(TimeScheme::BackwardEuler, 80) / 10);
}

TEST(Heat, DiffusionDampsASineModeAtItsRate) {
  // f = 0, g = 0, u0 = sin(πx) sin(πy): u = exp(−2π²κ t) u0.
  const Mesh2 mesh = unitSquareMesh(40);
  HeatProblem p;
  p.kappa = 0.05;
  p.dirichlet = [](double, double, double) { return 0.0; };
  HeatSolver solver(mesh, p, TimeScheme::BDF2);
  const auto mode = [](double x, double y) { return std::sin(std::numbers::pi * x) * std::sin(std::numbers::pi * y); };
  solver.setState(0, interpolate(mesh, mode));
  for (int n = 0; n < 50; ++n) solver.step(0.02);
  const double decay = std::exp(-2 * std::numbers::pi * std::numbers::pi * 0.05 * 1.0);
  const double err =
      computeErrors(mesh, solver.u(), {[&](double x, double y) { return decay * mode(x, y); }, {}, true}).l2;
  EXPECT_LT(err, 2e-3 * decay);
}

TEST(Heat, BadStepAndStateAreInputErrors) {
  const Mesh2 mesh = unitSquareMesh(4);
  HeatProblem p;
  p.dirichlet = uExact;
  HeatSolver solver(mesh, p, TimeScheme::BackwardEuler);
  EXPECT_THROW(solver.step(0.0), InputError);
  EXPECT_THROW(solver.step(-1.0), InputError);
  EXPECT_THROW(solver.setState(0, Eigen::VectorXd::Zero(3)), InputError);
  p.kappa = -1;
  EXPECT_THROW(HeatSolver(mesh, p, TimeScheme::BDF2), InputError);
  EXPECT_THROW(parseTimeScheme("rk4"), InputError);
}

TEST(TransientProblems, SourceIsTheTimeDerivativeMinusKappaLaplacian) {
  for (const auto& name : transientProblemNames()) {
    const TransientProblem p = makeTransientProblem(name);
    const double h = 1e-4;
    for (const Vec2& x : {Vec2(0.6, 0.55), Vec2(0.72, 0.4), Vec2(0.3, 0.5)})
      for (const double t : {0.05, 0.3}) {
        const auto u = [&](double dx, double dy, double dt) { return p.u(x.x() + dx, x.y() + dy, t + dt); };
        const double ut = (u(0, 0, h) - u(0, 0, -h)) / (2 * h);
        const double lap = (u(h, 0, 0) + u(-h, 0, 0) + u(0, h, 0) + u(0, -h, 0) - 4 * u(0, 0, 0)) / (h * h);
        const double scale = 1 + std::abs(ut) + p.kappa * std::abs(lap);
        EXPECT_NEAR(p.f(x.x(), x.y(), t), ut - p.kappa * lap, 1e-4 * scale) << name;
        const Vec2 g((u(h, 0, 0) - u(-h, 0, 0)) / (2 * h), (u(0, h, 0) - u(0, -h, 0)) / (2 * h));
        EXPECT_NEAR((p.grad(x.x(), x.y(), t) - g).norm(), 0, 1e-5 * (1 + g.norm())) << name;
      }
  }
  EXPECT_THROW(makeTransientProblem("movingpeak", {{"beta", 1}}), InputError);
  EXPECT_THROW(makeTransientProblem("wave"), InputError);
}
