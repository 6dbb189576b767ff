#include "ablmg/fem/solve.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/ordering.hpp"

#include <Eigen/CholmodSupport>

#include <algorithm>
#include <utility>
#include <vector>

namespace ablmg::fem {
namespace {

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

/// The lower triangle of P A Pᵀ (new index k = position of old index order[k]), each column's
/// rows sorted (CHOLMOD's `sorted` flag, set by Eigen's view, is then true). One pass over A;
/// the upper triangle, which CHOLMOD never reads for a lower-stored matrix, is not built.
Eigen::SparseMatrix<double> permutedLower(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order,
                                          const std::vector<int>& position) {
  const int n = int(A.rows());
  Eigen::SparseMatrix<double> L(n, n);
  std::vector<int> outer(std::size_t(n) + 1, 0);
  for (int k = 0; k < n; ++k) {
    int count = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, order[std::size_t(k)]); it; ++it)
      count += position[std::size_t(it.index())] >= k;
    outer[std::size_t(k) + 1] = outer[std::size_t(k)] + count;
  }
  L.resizeNonZeros(outer[std::size_t(n)]);
  std::copy(outer.begin(), outer.end(), L.outerIndexPtr());
  std::vector<std::pair<int, double>> column;
  for (int k = 0; k < n; ++k) {
    column.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, order[std::size_t(k)]); it; ++it) {
      const int row = position[std::size_t(it.index())];
      if (row >= k) column.emplace_back(row, it.value());
    }
    std::sort(column.begin(), column.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    int* rows = L.innerIndexPtr() + outer[std::size_t(k)];
    double* values = L.valuePtr() + outer[std::size_t(k)];
    for (std::size_t e = 0; e < column.size(); ++e) {
      rows[e] = column[e].first;
      values[e] = column[e].second;
    }
  }
  return L;
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
    std::vector<int> position(static_cast<std::size_t>(n));  // old index → new index
    for (int k = 0; k < int(n); ++k) position[std::size_t(order[std::size_t(k)])] = k;
    const Eigen::SparseMatrix<double> Ap = permutedLower(system.A, order, position);
    orderingSeconds = watch.seconds();
    // Our order, as it is: no fill-reducing permutation and no etree postorder by CHOLMOD.
    // Nested dissection with AMD leaves is close to a postorder already; CHOLMOD's weighted
    // postorder only reorders siblings (same flops and factor non-zeros), and with it the
    // factor counts as permuted, which makes cholmod_factorize transpose A twice per call.
    llt.cholmod().nmethods = 1;
    llt.cholmod().method[0].ordering = CHOLMOD_NATURAL;
    llt.cholmod().postorder = 0;
    factorise(llt, Ap);
    Eigen::VectorXd bp(n);
    for (Eigen::Index i = 0; i < n; ++i) bp[position[std::size_t(i)]] = system.b[i];
    const CholmodScope serial;
    const Eigen::VectorXd xp = llt.solve(bp);
    x.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = xp[position[std::size_t(i)]];
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
