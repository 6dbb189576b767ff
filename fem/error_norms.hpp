#pragma once
/// Errors of a P1 solution u_h against an exact solution u, by a degree-8 quadrature rule
/// (16 points per triangle; integrates the squared error of a smooth u to O(h^9) per element).
///
///   l2        = ‖u − u_h‖_{L2(Ω)}
///   h1        = |u − u_h|_{H1(Ω)} = ‖∇u − ∇u_h‖_{L2(Ω)}        (seminorm)
///   maxVertex = max_v |u(x_v) − u_h(v)|
///   l2Interp  = ‖u − I_h u‖_{L2(Ω)}, I_h u the nodal P1 interpolant (best-approximation
///               yardstick: on layer problems the FE L2 error is dominated by a smooth global
///               discrete error, so adaptive loops report both)
///   elementL2[t], elementH1[t]: the same norms restricted to triangle t (not squared), so
///               l2² = Σ elementL2[t]².
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace ablmg::fem {

/// ∇u. Beware: a lambda returning an Eigen expression (`return Vec2(a, b) * s;`) returns a
/// dangling expression; declare it `[](double x, double y) -> Vec2 { ... }`.
using GradientFn = std::function<Vec2(double x, double y)>;
/// u(x, y), with ∇u written to `grad`.
using ValueGradientFn = std::function<double(double x, double y, Vec2& grad)>;

struct ExactSolution {
  ScalarFn u;
  GradientFn grad;  ///< may be empty: then h1 and elementH1 are not computed (NaN / empty)
  /// True when u and grad may be called from several threads at once (pure lambdas, as
  /// TestProblem's); computeErrors() then runs in parallel, with bitwise the same result.
  bool threadSafe = false;
  /// Optional: u and ∇u at once (returns u, writes ∇u), for solutions whose two share work (a
  /// corner's r and θ). It must give the same values as u and grad; computeErrors then calls it
  /// instead of them.
  ValueGradientFn valueAndGrad = {};
};

struct ErrorReport {
  double l2 = 0, h1 = 0, maxVertex = 0, l2Interp = 0;
  std::vector<double> elementL2, elementH1;
};

/// All of the above. `uh` has one value per vertex. Throws InputError on a size mismatch or
/// an empty exact u. `degree` selects the rule (1…8; default 8).
ErrorReport computeErrors(const Mesh2& mesh, const Eigen::VectorXd& uh, const ExactSolution& exact, int degree = 8);

/// ‖u − I_h u‖_L2 alone (the nodal interpolant's error), same quadrature.
double interpolationErrorL2(const Mesh2& mesh, const ScalarFn& u, int degree = 8);

/// The nodal interpolant I_h u: u at each vertex.
Eigen::VectorXd interpolate(const Mesh2& mesh, const ScalarFn& u);

}  // namespace ablmg::fem
