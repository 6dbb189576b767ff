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
///  smooth      eˣ sin(πy) + x y                      (0,1)²   verification     (none)
///  sine        sin(πx) sin(πy)                      (0,1)²   verification     (none)
///  linear      1 + 2x − 3y  (f = 0, patch test)     (0,1)²   verification     (none)
///
/// Boundary tags: rectangles as Domain::rectangle (1 bottom, 2 right, 3 top, 4 left); the
/// L-shape's six segments are tagged 1…6 counter-clockwise from (0,0)→(1,0).
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
  ScalarFn f;  ///< −Δu

  ExactSolution exact() const { return {u, grad, true}; }
  /// κ = 1, f, Dirichlet data u on every boundary tag.
  PoissonProblem poisson() const;
};

/// Builds problem `name` with `params` overriding its defaults. Throws InputError naming the
/// valid problems (unknown name) or the problem's valid parameters (unknown key), or for an
/// invalid value (alpha ≤ 0, epsilon ≤ 0).
TestProblem makeProblem(const std::string& name, const std::map<std::string, double>& params = {});

/// Names accepted by makeProblem, in the table's order.
std::vector<std::string> problemNames();

}  // namespace ablmg::fem
