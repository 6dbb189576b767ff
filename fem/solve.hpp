#pragma once
/// Solving the assembled P1 Poisson system with CHOLMOD's supernodal Cholesky factorisation
/// (Eigen::CholmodSupernodalLLT, fill-reducing ordering chosen by CHOLMOD: AMD / METIS).
///
/// Errors (InputError, with the reason): the system is not SPD or is singular — κ ≤ 0, no
/// Dirichlet boundary (pure Neumann), a mesh piece without Dirichlet vertex (from assemble()),
/// or CHOLMOD reporting a non-positive pivot (names the column / vertex when it can).
#include "core/mesh2.hpp"
#include "fem/assemble.hpp"
#include "fem/poisson_problem.hpp"

#include <Eigen/Core>

namespace ablmg::fem {

struct SolveStats {
  double assemblySeconds = 0;  ///< wall time of assemble()
  double solveSeconds = 0;     ///< wall time of factorisation + triangular solves
  int unknowns = 0;            ///< free vertices (size of A)
  long nonZeros = 0;           ///< stored non-zeros of A (both halves)
  int dirichletVertices = 0;
  double residual = 0;         ///< ‖A x − b‖₂ / ‖b‖₂ of the computed solution (0 if b = 0)
};

struct PoissonSolution {
  Eigen::VectorXd u;  ///< per vertex, Dirichlet values included
  SolveStats stats;
};

/// Solves A x = b of an assembled system. Returns x (free unknowns only).
/// `stats` (optional) receives solveSeconds, unknowns, nonZeros, residual.
Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats = nullptr);

/// assemble() + solveSystem() + expand(): the P1 solution at every vertex of `mesh`.
PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem);

} // namespace ablmg::fem
