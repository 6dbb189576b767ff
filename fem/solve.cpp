#include "ablmg/fem/solve.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/ordering.hpp"

#include <Eigen/CholmodSupport>

// OpenBLAS's thread-count setter, if the BLAS loaded at run time is OpenBLAS (weak: null
// otherwise, e.g. with the reference BLAS, which is single-threaded anyway).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace ablmg::fem {
namespace {

/// The factorisation runs with one BLAS thread, whatever OMP_NUM_THREADS or
/// OPENBLAS_NUM_THREADS say. Two reasons:
///  - OpenBLAS's threaded dpotrf rounds differently for each thread count: one fixed count
///    gives the same bits on every machine;
///  - CHOLMOD's supernodal factorisation of a 2-D P1 matrix is thousands of small BLAS calls
///    (the largest front at 10⁶ unknowns is a few thousand columns). OpenBLAS's pthread pool
///    wakes and spins (sched_yield) on each call, and on a loaded machine or next to the
///    mesher's OpenMP threads a call waits for a descheduled helper: the factorisation of a
///    33k-unknown adapted mesh took 10–30 s wall in the adaptive loop on a shared 2-core
///    machine, 60 % of its samples in the kernel's scheduler, for 0.26 GFlop.
constexpr int kBlasThreads = 1;

void fixBlasThreads() {
  if (openblas_set_num_threads) openblas_set_num_threads(kBlasThreads);
}

using Cholesky = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

/// Factorises M with CHOLMOD; InputError if M is not SPD.
void factorise(Cholesky& llt, const Eigen::SparseMatrix<double>& M) {
  llt.cholmod().print = 0;  // libraries never print: CHOLMOD's warnings become our InputError
  fixBlasThreads();
  const CholmodScope serial;
  llt.compute(M);
  ABLMG_REQUIRE(llt.info() == Eigen::Success, "solve: CHOLMOD could not factorise the "
                                                  << M.rows() << "×" << M.rows()
                                                  << " stiffness matrix: it is not symmetric positive "
                                                     "definite (check kappa > 0 and the Dirichlet boundary)");
}

}  // namespace

Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats, const SolveOptions& options) {
  const Stopwatch watch;
  const Eigen::Index n = system.A.rows();
  ABLMG_REQUIRE(n > 0, "solve: the system has no unknowns (every vertex is a Dirichlet vertex)");
  Cholesky llt;
  Eigen::VectorXd x;
  double orderingSeconds = 0;
  if (options.ordering != Ordering::Cholmod) {
    ABLMG_REQUIRE(
        options.ordering == Ordering::Metis || Eigen::Index(system.dofPoints.size()) == n,
        "solve: geometric ordering needs dofPoints (" << system.dofPoints.size() << " for " << n << " unknowns)");
    const std::vector<int> order =
        options.ordering == Ordering::Metis
            ? metisNestedDissection(system.A)
            : geometricNestedDissection(system.A, system.dofPoints, options.leafSize, options.cut);
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P{int(n)};  // old index → new index
    for (int k = 0; k < int(n); ++k) P.indices()[order[k]] = k;
    Eigen::SparseMatrix<double> Ap;
    Ap = system.A.twistedBy(P);
    orderingSeconds = watch.seconds();
    llt.cholmod().nmethods = 1;
    llt.cholmod().method[0].ordering = CHOLMOD_NATURAL;  // keep ours
    factorise(llt, Ap);
    const Eigen::VectorXd bp = P * system.b;
    const CholmodScope serial;
    x = P.transpose() * llt.solve(bp);
  } else {
    factorise(llt, system.A);
    const CholmodScope serial;
    x = llt.solve(system.b);
  }
  ABLMG_REQUIRE(llt.info() == Eigen::Success && x.allFinite(),
                "solve: CHOLMOD's triangular solves failed (matrix " << n << "×" << n << ")");
  if (stats) {
    stats->solveSeconds = watch.seconds();
    stats->orderingSeconds = orderingSeconds;
    stats->unknowns = int(n);
    stats->nonZeros = long(system.A.nonZeros());
    stats->factorNonZeros = llt.cholmod().lnz;
    stats->factorFlops = llt.cholmod().fl;
    const double bn = system.b.norm();
    stats->residual = bn > 0 ? (system.A * x - system.b).norm() / bn : (system.A * x).norm();
  }
  return x;
}

PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem, const SolveOptions& options) {
  PoissonSolution sol;
  const Stopwatch watch;
  const LinearSystem sys = assemble(mesh, problem);
  sol.stats.assemblySeconds = watch.seconds();
  sol.stats.dirichletVertices = sys.numDirichletVertices;
  if (sys.A.rows() == 0) {  // every vertex Dirichlet: nothing to solve
    sol.u = sys.dirichletValues;
    return sol;
  }
  const Eigen::VectorXd x = solveSystem(sys, &sol.stats, options);
  sol.u = sys.expand(x);
  return sol;
}

}  // namespace ablmg::fem
