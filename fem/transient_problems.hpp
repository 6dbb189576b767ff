#pragma once
/// Time-dependent problems with known exact solutions, for the heat equation
///   u_t − κ Δu = f  in Ω × (t0, t1),   u = u_exact on ∂Ω,   u(·, t0) = u_exact(·, t0),
/// with f = u_t − κ Δu computed from the exact u (manufactured solutions). Their features
/// move, so a mesh adapted to u at one time is wrong a few steps later.
///
///  name        u                                                  params (defaults)
///  movingpeak  exp(−α |x − c(t)|²), c(t) = (xc + r cos ωt, yc + r sin ωt)
///                                  alpha 500, radius 0.25, omega π, xc 0.5, yc 0.5, kappa 0.01
///  front       tanh((x·n − v t − c)/ε), n = (cos θ, sin θ)
///                                  epsilon 0.02, speed 0.5, offset 0.25, angle π/6, kappa 0.01
///
/// Both on the unit square (tags as Domain::rectangle). Defaults of the time interval and step
/// (tStart 0; movingpeak tEnd 0.5, a quarter turn, the peak travels ≈ 12 widths; front tEnd 0.6,
/// ≈ 15 widths; dt 0.001: ≈ 40 steps per width) are in the problem and may be overridden. At
/// dt 0.002 BDF2's time error was about half of the space-time error of a 4000-vertex adaptive
/// run (halving dt: front 4.3e-5 → 2.0e-5, moving peak 4.0e-5 → 2.7e-5).
#include "ablmg/core/domain.hpp"
#include "ablmg/fem/error_norms.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ablmg::fem {

using SpaceTimeFn = std::function<double(double x, double y, double t)>;
using SpaceTimeGradientFn = std::function<Vec2(double x, double y, double t)>;

struct TransientProblem {
  std::string name;
  std::map<std::string, double> params;  ///< every parameter in effect (defaults included)
  std::string formula;                   ///< u as text, for reports
  Domain domain;
  double kappa = 1;                        ///< κ > 0
  double tStart = 0, tEnd = 1, dt = 0.01;  ///< suggested interval and step
  SpaceTimeFn u, f;                        ///< exact solution and source (thread-safe lambdas)
  SpaceTimeGradientFn grad;                ///< ∇u

  /// The exact solution at time t, for computeErrors (thread-safe).
  ExactSolution exactAt(double t) const;
};

/// Builds problem `name` with `params` overriding its defaults. Throws InputError naming the
/// valid problems (unknown name) or the valid parameters (unknown key), or for an invalid value.
TransientProblem makeTransientProblem(const std::string& name, const std::map<std::string, double>& params = {});

/// Names accepted by makeTransientProblem.
std::vector<std::string> transientProblemNames();

}  // namespace ablmg::fem
