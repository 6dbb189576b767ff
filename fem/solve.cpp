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

/// CHOLMOD's per-supernode overhead, not its flops, dominates a 2-D P1 factorisation at
/// 10⁵ unknowns: every supernode opens a few OpenMP regions (CHOLMOD's compiled-in loops; a
/// team of one under CholmodScope still costs an allocation and a futex round each) and a
/// handful of small BLAS calls. Two settings, both chosen by CHOLMOD's own symbolic counts
/// (deterministic: the same matrix takes the same path):
///  - supernodal = CHOLMOD_AUTO: a simplicial (up-looking) factorisation when the flops
///    per factor entry are below CHOLMOD's supernodal_switch (40), i.e. when the fronts are
///    too small for BLAS to pay. The tanh layer's adapted mesh (8.7·10⁴ unknowns, 0.05 GFlop,
///    flops/nnz 30) takes it: 0.18 → 0.12 s CPU; the uniform and wave-front meshes (170–210)
///    and the 10⁶ grid stay supernodal. final_ll: the simplicial path computes LLᵀ, whose
///    non-positive pivot is an error (LDLᵀ would accept an indefinite matrix).
///  - nrelax = {16, 64, 256} (CHOLMOD's defaults: 4, 16, 48): relaxed amalgamation merges
///    small supernodes, allowing explicit zeros. On the uniform 317² grid 2.4× fewer OpenMP
///    regions and 6.5 % fewer instructions (callgrind); {64, 256, 1024} doubles the
///    instructions (the zeros' flops), zrelax changes did not help; the 10⁶ grid unchanged.
/// Measured with bench/bench_solve_graded.cpp (docs/benchmarks.md, "Solver ordering").
void configureFactorisation(cholmod_common& c) {
  c.supernodal = CHOLMOD_AUTO;
  c.final_ll = 1;
  c.nrelax[0] = 16;
  c.nrelax[1] = 64;
  c.nrelax[2] = 256;
}

/// Factorises M with CHOLMOD; InputError if M is not SPD.
void factorise(Cholesky& llt, const Eigen::SparseMatrix<double>& M) {
  llt.cholmod().print = 0;  // libraries never print: CHOLMOD's warnings become our InputError
  configureFactorisation(llt.cholmod());
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
