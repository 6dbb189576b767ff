#pragma once
/// A library of Poisson problems −Δu = f with known exact solutions (u, ∇u, f = −Δu), their
/// domains and Dirichlet data (u on the whole boundary), for verification and adaptivity.
///
/// Reference: W. F. Mitchell, "A collection of 2D elliptic problems for testing adaptive grid
/// refinement algorithms", Appl. Math. Comput. 220 (2013) 350–364.
///
///  name        u                                   domain                    params (defaults)
///  wavefront   atan(α (r − r0)), r = |x − (xc,yc)|  (0,1)²   Mitchell: wave front      alpha 20, xc −0.05, yc −0.05, r0 0.7
///  peak        exp(−α |x − (xc,yc)|²)               (0,1)²   Mitchell: peak            alpha 1000, xc 0.5, yc 0.5
///  lshape      r^(2/3) sin(2θ/3), θ ∈ [0, 3π/2]     (−1,1)² \ [0,1)×(−1,0]    Mitchell: reentrant corner (f = 0)
///  tanhlayer   tanh((y − 0.5)/ε)                    (0,1)²   anisotropic interior layer   epsilon 0.01
///  reentrant   r^(π/ω) sin(πθ/ω), θ ∈ [0, ω]        (−1,1)² \ {ω < θ < 2π}   Mitchell: reentrant corner   omega 7π/4 (∈ (π, 2π], radians;
///                                                   2π: the slit [0,1)×{0}, lips distinct: Domain slits)
///  linesing    cos(πy/2) + max(x − β(y+1), 0)^α     (−1,1)²  Mitchell: interior line singularity   alpha 2.5, beta 0.6
///  multiple    r^(2/3) sin(2θ/3) + exp(−α_p ρ_p²)   the L-shape   Mitchell: multiple difficulties (corner, peak,
///              + atan(α_w(r_w − r0)) + exp(−(1+y)/ε)      front, layer at y = −1)   alpha_p 1000, xp −√5/4, yp −1/4,
///                                                          alpha_w 200, xw 0, yw −3/4, r0 3/4, epsilon 0.01
///  smooth      eˣ sin(πy) + x y                      (0,1)²   verification     (none)
///  sine        sin(πx) sin(πy)                      (0,1)²   verification     (none)
///  linear      1 + 2x − 3y  (f = 0, patch test)     (0,1)²   verification     (none)
///
/// Boundary tags: rectangles as Domain::rectangle (1 bottom, 2 right, 3 top, 4 left); the
/// L-shape's six segments (and the reentrant domain's) are tagged 1, 2, … counter-clockwise from
/// (0,0)→(1,0). The load f is a function; the solver integrates it by quadrature (fem/assemble.hpp),
/// with a degree-5 rule. linesing's load has the term s^(α−2): for α < 2 (Mitchell's harder
/// choices 1.5 and 1.1) it is singular along the line, its quadrature error then dominates the
/// FE L2 error (for FreeFem++'s degree-7 rule too: both L2 errors rise between some cycles while
/// the interpolation error falls), so the default is Mitchell's α = 2.5 (a bounded, Hölder load).
#include "ablmg/core/domain.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <map>
#include <string>
#include <vector>

namespace ablmg::fem {

struct TestProblem {
  std::string name;
  std::map<std::string, double> params;  ///< every parameter in effect (defaults included)
  std::string formula;                   ///< u as text, for reports
  Domain domain;
  ScalarFn u;
  GradientFn grad;
  ScalarFn f;                         ///< −Δu
  ValueGradientFn valueAndGrad = {};  ///< u and ∇u at once where they share work (else empty)

  ExactSolution exact() const { return {u, grad, true, valueAndGrad}; }
  /// κ = 1, f, Dirichlet data u on every boundary tag.
  PoissonProblem poisson() const;
};

/// Builds problem `name` with `params` overriding its defaults. Throws InputError naming the
/// valid problems (unknown name) or the problem's valid parameters (unknown key), or for an
/// invalid value (alpha ≤ 0, epsilon ≤ 0, omega ∉ (π, 2π], linesing alpha ≤ 1).
TestProblem makeProblem(const std::string& name, const std::map<std::string, double>& params = {});

/// Names accepted by makeProblem, in the table's order.
std::vector<std::string> problemNames();

}  // namespace ablmg::fem
