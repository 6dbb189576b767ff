#include "fem/solve.hpp"

#include "core/error.hpp"

#include <Eigen/CholmodSupport>

#include <chrono>

namespace ablmg::fem {
namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = system.A.rows();
  ABLMG_REQUIRE(n > 0, "solve: the system has no unknowns (every vertex is a Dirichlet vertex)");
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  llt.cholmod().print = 0;  // libraries never print: CHOLMOD's warnings become our InputError
  llt.compute(system.A);
  if (llt.info() != Eigen::Success) {
    ABLMG_REQUIRE(false, "solve: CHOLMOD could not factorise the " << n << "×" << n
                                                                    << " stiffness matrix: it is not symmetric "
                                                                       "positive definite (check kappa > 0 and "
                                                                       "the Dirichlet boundary)");
  }
  Eigen::VectorXd x = llt.solve(system.b);
  ABLMG_REQUIRE(llt.info() == Eigen::Success && x.allFinite(),
                "solve: CHOLMOD's triangular solves failed (matrix " << n << "×" << n << ")");
  if (stats) {
    stats->solveSeconds = secondsSince(t0);
    stats->unknowns = int(n);
    stats->nonZeros = long(system.A.nonZeros());
    const double bn = system.b.norm();
    stats->residual = bn > 0 ? (system.A * x - system.b).norm() / bn : (system.A * x).norm();
  }
  return x;
}

PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem) {
  PoissonSolution sol;
  const auto t0 = std::chrono::steady_clock::now();
  const LinearSystem sys = assemble(mesh, problem);
  sol.stats.assemblySeconds = secondsSince(t0);
  sol.stats.dirichletVertices = sys.numDirichletVertices;
  if (sys.A.rows() == 0) {  // every vertex Dirichlet: nothing to solve
    sol.u = sys.dirichletValues;
    return sol;
  }
  const Eigen::VectorXd x = solveSystem(sys, &sol.stats);
  sol.u = sys.expand(x);
  return sol;
}

} // namespace ablmg::fem
