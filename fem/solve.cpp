#include "ablmg/fem/solve.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/ordering.hpp"
#include "ablmg/fem/split_cholesky.hpp"

#include <Eigen/CholmodSupport>

#include <algorithm>
#include <utility>
#include <vector>

namespace ablmg::fem {
namespace {

using Cholesky = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

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

/// Factorises M with CHOLMOD (analysis, then numeric factorisation, timed apart in `stats`);
/// InputError if M is not SPD.
void factorise(Cholesky& llt, const Eigen::SparseMatrix<double>& M, SolveStats* stats) {
  llt.cholmod().print = 0;  // libraries never print: CHOLMOD's warnings become our InputError
  configureFactorisation(llt.cholmod());
  fixBlasThreads();
  const CholmodScope serial;
  Stopwatch watch;
  llt.analyzePattern(M);
  const double symbolic = watch.lap();
  if (llt.info() == Eigen::Success) llt.factorize(M);
  if (stats) {
    stats->symbolicSeconds = symbolic;
    stats->numericSeconds = watch.seconds();
  }
  ABLMG_REQUIRE(llt.info() == Eigen::Success, "solve: CHOLMOD could not factorise the "
                                                  << M.rows() << "×" << M.rows()
                                                  << " stiffness matrix: it is not symmetric positive "
                                                     "definite (check kappa > 0 and the Dirichlet boundary)");
}

/// One CHOLMOD factorisation of the whole matrix: with our order (`order` non-empty) CHOLMOD
/// gets the lower triangle of P A Pᵀ and keeps the order as it is, else CHOLMOD orders.
Eigen::VectorXd solveWhole(const LinearSystem& system, const std::vector<int>& order, const std::vector<int>& position,
                           SolveStats* stats) {
  const Eigen::Index n = system.A.rows();
  Cholesky llt;
  Eigen::VectorXd x;
  if (!order.empty()) {
    const Stopwatch permuting;
    const Eigen::SparseMatrix<double> Ap = permutedLower(system.A, order, position);
    const double tPermute = permuting.seconds();
    // Our order, as it is: no fill-reducing permutation and no etree postorder by CHOLMOD.
    // Nested dissection with AMD leaves is close to a postorder already; CHOLMOD's weighted
    // postorder only reorders siblings (same flops and factor non-zeros), and with it the
    // factor counts as permuted, which makes cholmod_factorize transpose A twice per call.
    llt.cholmod().nmethods = 1;
    llt.cholmod().method[0].ordering = CHOLMOD_NATURAL;
    llt.cholmod().postorder = 0;
    factorise(llt, Ap, stats);
    if (stats) stats->symbolicSeconds += tPermute;
    const Stopwatch watch;
    Eigen::VectorXd bp(n);
    for (Eigen::Index i = 0; i < n; ++i) bp[position[std::size_t(i)]] = system.b[i];
    const CholmodScope serial;
    const Eigen::VectorXd xp = llt.solve(bp);
    x.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = xp[position[std::size_t(i)]];
    if (stats) stats->triangularSeconds = watch.seconds();
  } else {
    factorise(llt, system.A, stats);
    const Stopwatch watch;
    const CholmodScope serial;
    x = llt.solve(system.b);
    if (stats) stats->triangularSeconds = watch.seconds();
  }
  ABLMG_REQUIRE(llt.info() == Eigen::Success && x.allFinite(),
                "solve: CHOLMOD's triangular solves failed (matrix " << n << "×" << n << ")");
  if (stats) {
    stats->factorNonZeros = llt.cholmod().lnz;
    stats->factorFlops = llt.cholmod().fl;
  }
  return x;
}

}  // namespace

Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats, const SolveOptions& options) {
  const Stopwatch watch;
  const Eigen::Index n = system.A.rows();
  ABLMG_REQUIRE(n > 0, "solve: the system has no unknowns (every vertex is a Dirichlet vertex)");
  SolveStats local;
  SolveStats& st = stats ? *stats : local;
  std::vector<int> order, position;
  TopCut top;
  if (options.ordering != Ordering::Cholmod) {
    ABLMG_REQUIRE(
        options.ordering == Ordering::Metis || Eigen::Index(system.dofPoints.size()) == n,
        "solve: geometric ordering needs dofPoints (" << system.dofPoints.size() << " for " << n << " unknowns)");
    order = options.ordering == Ordering::Metis
                ? metisNestedDissection(system.A)
                : geometricNestedDissection(system.A, system.dofPoints, options.leafSize, options.cut, &top);
    position.resize(static_cast<std::size_t>(n));  // old index → new index
    for (int k = 0; k < int(n); ++k) position[std::size_t(order[std::size_t(k)])] = k;
  }
  st.orderingSeconds = watch.seconds();
  Eigen::VectorXd x;
  if (n >= options.splitMinUnknowns && top.lower > 0 && top.upper > 0) {
    SplitCholeskyStats split;
    x = splitCholeskySolve(system.A, order, position, top.lower, top.upper, system.b, &split);
    ABLMG_REQUIRE(x.allFinite(),
                  "solve: the triangular solves gave non-finite values (matrix " << n << "×" << n << ")");
    st.symbolicSeconds = split.symbolicSeconds;
    st.numericSeconds = split.numericSeconds;
    st.triangularSeconds = split.solveSeconds;
    st.factorNonZeros = split.factorNonZeros;
    st.factorFlops = split.factorFlops;
  } else {
    x = solveWhole(system, order, position, &st);
  }
  st.solveSeconds = watch.seconds();
  st.unknowns = int(n);
  st.nonZeros = long(system.A.nonZeros());
  if (stats) {
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
