#include "ablmg/fem/solve.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/ordering.hpp"
#include "ablmg/fem/split_cholesky.hpp"

#include <Eigen/CholmodSupport>

#include <algorithm>
#include <cstring>
#include <memory>
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

}  // namespace

/// The order (empty: CHOLMOD orders), and either the split factorisation of the first cut or
/// one CHOLMOD factorisation (of P A Pᵀ's lower triangle with our order, else of A).
struct Factorisation::Impl {
  Eigen::SparseMatrix<double> owned;  ///< A, when the factorisation keeps it
  const Eigen::SparseMatrix<double>* A = nullptr;
  std::vector<int> order, position;
  std::unique_ptr<SplitCholesky> split;
  std::unique_ptr<Cholesky> whole;
  double factorNonZeros = 0, factorFlops = 0;

  /// Orders and factorises *A (which must outlive the solves); stats: ordering, symbolic,
  /// numeric and the counts.
  void factorise(const std::vector<Vec2>& points, const SolveOptions& options, SolveStats& st);
  Eigen::VectorXd solve(const Eigen::VectorXd& b, SolveStats* stats);
};

void Factorisation::Impl::factorise(const std::vector<Vec2>& points, const SolveOptions& options, SolveStats& st) {
  const Stopwatch watch;
  const Eigen::Index n = A->rows();
  ABLMG_REQUIRE(n > 0, "solve: the system has no unknowns (every vertex is a Dirichlet vertex)");
  TopCut top;
  if (options.ordering != Ordering::Cholmod) {
    ABLMG_REQUIRE(options.ordering == Ordering::Metis || Eigen::Index(points.size()) == n,
                  "solve: geometric ordering needs dofPoints (" << points.size() << " for " << n << " unknowns)");
    order = options.ordering == Ordering::Metis
                ? metisNestedDissection(*A)
                : geometricNestedDissection(*A, points, options.leafSize, options.cut, &top);
    position.resize(static_cast<std::size_t>(n));  // old index → new index
    for (int k = 0; k < int(n); ++k) position[std::size_t(order[std::size_t(k)])] = k;
  }
  st.orderingSeconds = watch.seconds();
  if (n >= options.splitMinUnknowns && top.lower > 0 && top.upper > 0) {
    SplitCholeskyStats s;
    split = std::make_unique<SplitCholesky>(*A, order, position, top.lower, top.upper, &s);
    st.symbolicSeconds = s.symbolicSeconds;
    st.numericSeconds = s.numericSeconds;
    factorNonZeros = s.factorNonZeros;
    factorFlops = s.factorFlops;
  } else {
    whole = std::make_unique<Cholesky>();
    if (!order.empty()) {
      const Stopwatch permuting;
      const Eigen::SparseMatrix<double> Ap = permutedLower(*A, order, position);
      const double tPermute = permuting.seconds();
      // Our order, as it is: no fill-reducing permutation and no etree postorder by CHOLMOD.
      // Nested dissection with AMD leaves is close to a postorder already; CHOLMOD's weighted
      // postorder only reorders siblings (same flops and factor non-zeros), and with it the
      // factor counts as permuted, which makes cholmod_factorize transpose A twice per call.
      whole->cholmod().nmethods = 1;
      whole->cholmod().method[0].ordering = CHOLMOD_NATURAL;
      whole->cholmod().postorder = 0;
      fem::factorise(*whole, Ap, &st);
      st.symbolicSeconds += tPermute;
    } else {
      fem::factorise(*whole, *A, &st);
    }
    factorNonZeros = whole->cholmod().lnz;
    factorFlops = whole->cholmod().fl;
  }
  st.factorNonZeros = factorNonZeros;
  st.factorFlops = factorFlops;
}

Eigen::VectorXd Factorisation::Impl::solve(const Eigen::VectorXd& b, SolveStats* stats) {
  const Eigen::Index n = A->rows();
  ABLMG_REQUIRE(b.size() == n, "solve: right-hand side of " << b.size() << " entries for " << n << " unknowns");
  const Stopwatch watch;
  Eigen::VectorXd x;
  if (split) {
    x = split->solve(b);
  } else if (!order.empty()) {
    Eigen::VectorXd bp(n);
    for (Eigen::Index i = 0; i < n; ++i) bp[position[std::size_t(i)]] = b[i];
    const CholmodScope serial;
    const Eigen::VectorXd xp = whole->solve(bp);
    ABLMG_REQUIRE(whole->info() == Eigen::Success,
                  "solve: CHOLMOD's triangular solves failed (matrix " << n << "×" << n << ")");
    x.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = xp[position[std::size_t(i)]];
  } else {
    const CholmodScope serial;
    x = whole->solve(b);
    ABLMG_REQUIRE(whole->info() == Eigen::Success,
                  "solve: CHOLMOD's triangular solves failed (matrix " << n << "×" << n << ")");
  }
  ABLMG_REQUIRE(x.allFinite(), "solve: the triangular solves gave non-finite values (matrix " << n << "×" << n << ")");
  if (stats) {
    stats->triangularSeconds = watch.seconds();
    stats->factorNonZeros = factorNonZeros;
    stats->factorFlops = factorFlops;
  }
  return x;
}

Factorisation::Factorisation(const LinearSystem& system, const SolveOptions& options, SolveStats* stats)
    : Factorisation(Eigen::SparseMatrix<double>(system.A), system.dofPoints, options, stats) {}

Factorisation::Factorisation(Eigen::SparseMatrix<double>&& A, const std::vector<Vec2>& points,
                             const SolveOptions& options, SolveStats* stats)
    : impl_(std::make_unique<Impl>()) {
  impl_->owned = std::move(A);
  impl_->owned.makeCompressed();
  impl_->A = &impl_->owned;
  SolveStats local;
  impl_->factorise(points, options, stats ? *stats : local);
}

Factorisation::~Factorisation() = default;
Factorisation::Factorisation(Factorisation&&) noexcept = default;
Factorisation& Factorisation::operator=(Factorisation&&) noexcept = default;

Eigen::VectorXd Factorisation::solve(const Eigen::VectorXd& b, SolveStats* stats) { return impl_->solve(b, stats); }

const Eigen::SparseMatrix<double>& Factorisation::matrix() const { return *impl_->A; }

bool Factorisation::sameMatrix(const Eigen::SparseMatrix<double>& B) const {
  const Eigen::SparseMatrix<double>& A = *impl_->A;
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros() || !B.isCompressed()) return false;
  const std::size_t nz = std::size_t(A.nonZeros()), cols = std::size_t(A.cols()) + 1;
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + cols, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + nz, B.innerIndexPtr()) &&
         std::memcmp(A.valuePtr(), B.valuePtr(), nz * sizeof(double)) == 0;  // bits, not ==
}

namespace {

/// The fields every solve fills: the total time, the sizes and the residual.
void finishStats(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                 double seconds, SolveStats& st) {
  st.solveSeconds = seconds;
  st.unknowns = int(A.rows());
  st.nonZeros = long(A.nonZeros());
  const double bn = b.norm();
  st.residual = bn > 0 ? (A * x - b).norm() / bn : (A * x).norm();
}

}  // namespace

Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats, const SolveOptions& options) {
  const Stopwatch watch;
  SolveStats local;
  SolveStats& st = stats ? *stats : local;
  Factorisation::Impl f;  // A not copied: the system outlives the solve
  f.A = &system.A;
  f.factorise(system.dofPoints, options, st);
  const Eigen::VectorXd x = f.solve(system.b, &st);
  const double seconds = watch.seconds();
  if (stats) finishStats(system.A, system.b, x, seconds, st);
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

PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem, const SolveOptions& options,
                             std::unique_ptr<Factorisation>& factor) {
  PoissonSolution sol;
  Stopwatch watch;
  LinearSystem sys = assemble(mesh, problem);
  sol.stats.assemblySeconds = watch.lap();
  sol.stats.dirichletVertices = sys.numDirichletVertices;
  if (sys.A.rows() == 0) {  // every vertex Dirichlet: nothing to solve
    sol.u = sys.dirichletValues;
    return sol;
  }
  if (!factor || !factor->sameMatrix(sys.A)) {
    factor.reset();  // the old factor's memory back before the new one is made
    factor = std::make_unique<Factorisation>(std::move(sys.A), sys.dofPoints, options, &sol.stats);
  }
  const Eigen::VectorXd x = factor->solve(sys.b, &sol.stats);
  finishStats(factor->matrix(), sys.b, x, watch.seconds(), sol.stats);
  sol.u = sys.expand(x);
  return sol;
}

}  // namespace ablmg::fem
