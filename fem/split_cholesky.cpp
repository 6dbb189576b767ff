#include "ablmg/fem/split_cholesky.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"

#include <cholmod.h>
#include <omp.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <system_error>
#include <thread>
#include <utility>

// LAPACK / BLAS (Fortran interface; the trailing arguments are the hidden lengths of the
// character arguments).
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info, std::size_t);
void dlauum_(const char* uplo, const int* n, double* a, const int* lda, int* info, std::size_t);
void dtrmv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx, std::size_t, std::size_t, std::size_t);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx, std::size_t, std::size_t, std::size_t);
}

namespace ablmg::fem {
namespace {

/// One side of the cut: its matrix [M_kk M_k3; M_3k M₃₃] (lower triangle, local numbering:
/// the side's unknowns, then the separator's), CHOLMOD's factor of it, and T_k T_kᵀ.
struct Side {
  int first = 0;  ///< first new index of the side
  int count = 0;  ///< its number of unknowns
  Eigen::SparseMatrix<double> M;
  cholmod_common c{};
  cholmod_factor* L = nullptr;
  Eigen::MatrixXd T;  ///< trailing n_s × n_s block of the factor (lower; upper part 0)
  Eigen::MatrixXd P;  ///< T Tᵀ (lower part; freed once S is formed)

  Side() { cholmod_start(&c); }
  ~Side() {
    release();
    cholmod_finish(&c);
  }
  /// Frees the factor and the blocks (CHOLMOD's counts in c stay).
  void release() {
    if (L) cholmod_free_factor(&L, &c);
    Eigen::SparseMatrix<double>().swap(M);
    T.resize(0, 0);
    P.resize(0, 0);
  }
  Side(const Side&) = delete;
  Side& operator=(const Side&) = delete;
};

/// Side s's matrix, built from A and the order in one pass over its columns (rows sorted).
/// An entry of A joining the two sides violates the cut: Error.
void buildSideMatrix(Side& s, const Eigen::SparseMatrix<double>& A, const std::vector<int>& order,
                     const std::vector<int>& position, int sepFirst) {
  const int n = int(A.rows()), ns = n - sepFirst, m = s.count + ns;
  const auto local = [&](int k) { return k >= sepFirst ? s.count + k - sepFirst : k - s.first; };
  const auto global = [&](int j) { return order[std::size_t(j < s.count ? s.first + j : sepFirst + j - s.count)]; };
  std::vector<int> outer(std::size_t(m) + 1, 0);
  std::vector<std::pair<int, double>> column;
  std::vector<int> rows;
  std::vector<double> values;
  rows.reserve(std::size_t(A.nonZeros()) * std::size_t(m) / std::size_t(2 * n) + std::size_t(m));
  values.reserve(rows.capacity());
  for (int j = 0; j < m; ++j) {
    column.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, global(j)); it; ++it) {
      const int k = position[std::size_t(it.index())];
      if (j >= s.count && k < sepFirst) continue;  // a side's row of a separator column: upper triangle
      ABLMG_ASSERT(k >= sepFirst || (k >= s.first && k < s.first + s.count),
                   "splitCholeskySolve: an entry of A joins the two sides of the cut");
      const int row = local(k);
      if (row >= j) column.emplace_back(row, it.value());
    }
    std::sort(column.begin(), column.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [row, value] : column) {
      rows.push_back(row);
      values.push_back(value);
    }
    outer[std::size_t(j) + 1] = int(rows.size());
  }
  s.M.resize(m, m);
  s.M.resizeNonZeros(Eigen::Index(rows.size()));
  std::copy(outer.begin(), outer.end(), s.M.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), s.M.innerIndexPtr());
  std::copy(values.begin(), values.end(), s.M.valuePtr());
}

/// CHOLMOD's view of a lower-stored, compressed, sorted Eigen matrix (no copy).
cholmod_sparse viewLower(Eigen::SparseMatrix<double>& M) {
  cholmod_sparse v{};
  v.nrow = v.ncol = std::size_t(M.rows());
  v.nzmax = std::size_t(M.nonZeros());
  v.p = M.outerIndexPtr();
  v.i = M.innerIndexPtr();
  v.x = M.valuePtr();
  v.stype = -1;
  v.itype = CHOLMOD_INT;
  v.xtype = CHOLMOD_REAL;
  v.dtype = CHOLMOD_DOUBLE;
  v.sorted = 1;
  v.packed = 1;
  return v;
}

/// The trailing n_s × n_s block of CHOLMOD's LLᵀ factor (supernodal or simplicial).
Eigen::MatrixXd trailingBlock(const cholmod_factor& L, int first) {
  const int n = int(L.n), ns = n - first;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(ns, ns);
  const double* x = static_cast<const double*>(L.x);
  if (L.is_super) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* ls = static_cast<const int*>(L.s);
    for (std::size_t s = 0; s < L.nsuper; ++s) {
      const int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s];
      for (int j = std::max(k1, first); j < k2; ++j)
        for (int i = j - k1; i < nsrow; ++i) T(ls[pi[s] + i] - first, j - first) = x[px[s] + i + (j - k1) * nsrow];
    }
  } else {
    const int* p = static_cast<const int*>(L.p);
    const int* nz = static_cast<const int*>(L.nz);
    const int* li = static_cast<const int*>(L.i);
    for (int j = first; j < n; ++j)
      for (int q = p[j]; q < p[j] + nz[j]; ++q) T(li[q] - first, j - first) = x[q];
  }
  return T;
}

/// T Tᵀ of a lower triangular T (lower part), in n³/3 flops: with J the order reversal,
/// J T J is upper triangular and T Tᵀ = J (J T J)(J T J)ᵀ J, which LAPACK's dlauum forms.
Eigen::MatrixXd lowerTimesTranspose(const Eigen::MatrixXd& T) {
  const int n = int(T.rows());
  Eigen::MatrixXd U = T.reverse();  // (J T J)(i, j) = T(n−1−i, n−1−j)
  int info = 0;
  dlauum_("U", &n, U.data(), &n, &info, 1);
  ABLMG_ASSERT(info == 0, "dlauum: argument " << -info);
  return U.reverse();
}

/// CHOLMOD's symbolic analysis of side s, our order kept (no permutation, no postorder).
void analyseSide(Side& s) {
  configureFactorisation(s.c);
  s.c.print = 0;
  s.c.nmethods = 1;
  s.c.method[0].ordering = CHOLMOD_NATURAL;
  s.c.postorder = 0;
  cholmod_sparse v = viewLower(s.M);
  s.L = cholmod_analyze(&v, &s.c);
  ABLMG_REQUIRE(s.L && s.c.status == CHOLMOD_OK, "solve: CHOLMOD's analysis failed (status " << s.c.status << ")");
}

/// Allocates the values of side s's supernodal factor and maps their pages in one call, on
/// the calling thread, before CHOLMOD fills them. CHOLMOD's own path mallocs L->x (≈ 375 MB
/// per side at 10⁶ unknowns) and zeroes it supernode by supernode, and each first touch of a
/// 4 KB page is then a page fault: 2.6–2.7 µs per page on this machine (a C loop over 375 MB:
/// 0.25–0.27 s), against 1.7–1.8 µs for MADV_POPULATE_WRITE (Linux ≥ 5.14; 0.16–0.18 s).
/// Transparent huge pages were worse here (the kernel compacts and zeroes 2 MB pages: +2 CPU s
/// at 10⁶). A simplicial factor, an older kernel or a failed call: CHOLMOD allocates as before.
/// The factor's values are the same either way (CHOLMOD writes every entry before reading it).
void prefaultFactor(Side& s) {
#ifdef MADV_POPULATE_WRITE
  constexpr std::size_t kMinBytes = std::size_t(1) << 20;  // below, a few hundred faults at most
  if (!s.L->is_super || s.L->xtype != CHOLMOD_PATTERN || s.L->xsize * sizeof(double) < kMinBytes) return;
  if (!cholmod_change_factor(CHOLMOD_REAL, true, true, true, true, s.L, &s.c)) return;
  const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
  const auto first = (reinterpret_cast<std::uintptr_t>(s.L->x) + page - 1) / page * page;
  const auto last = (reinterpret_cast<std::uintptr_t>(s.L->x) + s.L->xsize * sizeof(double)) / page * page;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);  // a hint only
#else
  (void)s;
#endif
}

/// The numeric factorisation of side s, then T and P = T Tᵀ.
void factoriseSide(Side& s) {
  prefaultFactor(s);
  cholmod_sparse v = viewLower(s.M);
  cholmod_factorize(&v, s.L, &s.c);
  ABLMG_REQUIRE(s.c.status >= CHOLMOD_OK && s.L->minor == s.L->n && s.L->is_ll,
                "solve: CHOLMOD could not factorise the " << s.M.rows()
                                                          << "-unknown side of the stiffness matrix: it is not "
                                                             "symmetric positive definite (check kappa > 0 and the "
                                                             "Dirichlet boundary)");
  s.T = trailingBlock(*s.L, s.count);
  s.P = lowerTimesTranspose(s.T);
}

/// x := op(L) x or op(L)⁻¹ x on side s's factor (sys = CHOLMOD_L or CHOLMOD_Lt).
Eigen::VectorXd solveSide(Side& s, int sys, const Eigen::VectorXd& rhs) {
  cholmod_dense b{};
  b.nrow = b.nzmax = std::size_t(rhs.size());
  b.ncol = 1;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data());  // read only
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* r = cholmod_solve(sys, s.L, &b, &s.c);
  ABLMG_REQUIRE(r && s.c.status == CHOLMOD_OK, "solve: CHOLMOD's triangular solve failed");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(r->x), rhs.size());
  cholmod_free_dense(&r, &s.c);
  return out;
}

/// Runs f(0) on the calling thread and f(1) on a thread of its own when `parallel` (else
/// both on the calling thread), each inside a CholmodScope. The second side runs on a plain
/// std::thread, not in an OpenMP team: a thread in no parallel region runs CHOLMOD's
/// per-supernode OpenMP regions without a team (fem/cholmod_threads.hpp), where a team
/// member would pay a nested team of one per region. The error of side 0 wins over side 1's.
template <class F>
void onBothSides(bool parallel, F&& f) {
  ParallelFailure failure;
  const auto side = [&](int k) {
    failure.run(k, [&] {
      const CholmodScope serial;
      f(k);
    });
  };
  std::thread other;
  if (parallel) {
    try {
      other = std::thread(side, 1);
    } catch (const std::system_error&) {  // no thread to be had: one side after the other
    }
  }
  side(0);
  if (other.joinable())
    other.join();
  else
    side(1);
  failure.rethrow();
}

/// S = P₁ + P₂ − M₃₃ (lower part), factorised in place: L₃₃.
Eigen::MatrixXd separatorFactor(const Side (&side)[2]) {
  const Side& s = side[0];
  const int ns = int(s.P.rows());
  Eigen::MatrixXd S(ns, ns);
  for (int j = 0; j < ns; ++j)
    for (int i = j; i < ns; ++i) S(i, j) = side[0].P(i, j) + side[1].P(i, j);
  for (int j = 0; j < ns; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.M, s.count + j); it; ++it)
      S(it.index() - s.count, j) -= it.value();
  int info = 0;
  dpotrf_("L", &ns, S.data(), &ns, &info, 1);
  ABLMG_REQUIRE(info == 0,
                "solve: the stiffness matrix is not symmetric positive definite (the separator's "
                "Schur complement has a non-positive pivot at "
                    << info << "; check kappa > 0 and the Dirichlet boundary)");
  return S;
}

}  // namespace

struct SplitCholesky::Impl {
  std::vector<int> order;
  int n = 0, sepFirst = 0, ns = 0;
  bool parallel = false;
  Side side[2];
  Eigen::MatrixXd L33;
};

SplitCholesky::SplitCholesky(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order,
                             const std::vector<int>& position, int lower, int upper, SplitCholeskyStats* stats)
    : impl_(std::make_unique<Impl>()) {
  Impl& f = *impl_;
  f.n = int(A.rows());
  f.sepFirst = lower + upper;
  f.ns = f.n - f.sepFirst;
  ABLMG_REQUIRE(lower >= 1 && upper >= 1 && f.ns >= 1 && int(order.size()) == f.n && int(position.size()) == f.n,
                "splitCholeskySolve: sides " << lower << " + " << upper << " of " << f.n << " unknowns");
  f.order = order;
  fixBlasThreads();
  f.parallel = omp_get_max_threads() > 1 && !omp_in_parallel();
  Side(&side)[2] = f.side;
  side[0].count = lower;
  side[1].first = lower;
  side[1].count = upper;
  Stopwatch watch;
  onBothSides(f.parallel, [&](int k) {
    buildSideMatrix(side[k], A, order, position, f.sepFirst);
    analyseSide(side[k]);
  });
  const double tSymbolic = watch.lap();
  onBothSides(f.parallel, [&](int k) { factoriseSide(side[k]); });
  f.L33 = separatorFactor(side);
  for (Side& s : side) {  // the solves need T and the factor only
    s.P.resize(0, 0);
    Eigen::SparseMatrix<double>().swap(s.M);
  }
  if (stats) {
    stats->symbolicSeconds = tSymbolic;
    stats->numericSeconds = watch.seconds();
    const double ns = f.ns, dense = 0.5 * ns * (ns + 1), cube = ns * ns * ns;
    stats->factorNonZeros = side[0].c.lnz + side[1].c.lnz - dense;
    stats->factorFlops = side[0].c.fl + side[1].c.fl + cube;  // 2 × T Tᵀ + chol(S): n_s³/3 each
  }
}

SplitCholesky::~SplitCholesky() {
  // Each side's factor (≈ 0.4 GB at 10⁶ unknowns) goes back on its own thread: returning its
  // pages costs ≈ 0.03 s CPU per side, which the calling thread alone would pay.
  if (impl_) {
    try {
      onBothSides(impl_->parallel, [&](int k) { impl_->side[k].release(); });
    } catch (...) {  // release() does not throw; the side's destructor frees what is left
    }
  }
}

Eigen::VectorXd SplitCholesky::solve(const Eigen::VectorXd& b) {
  Impl& f = *impl_;
  const int n = f.n, ns = f.ns, sepFirst = f.sepFirst;
  const std::vector<int>& order = f.order;
  ABLMG_REQUIRE(b.size() == n,
                "splitCholeskySolve: right-hand side of " << b.size() << " entries for " << n << " unknowns");
  Side(&side)[2] = f.side;
  // Forward: side k solves L⁽ᵏ⁾ [y_k; z_k] = [b_k; 0], so that L_3k y_k = −T_k z_k.
  const int one = 1;
  Eigen::VectorXd y[2], u[2];
  onBothSides(f.parallel, [&](int k) {
    Side& s = side[k];
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(s.count + ns);
    for (int j = 0; j < s.count; ++j) rhs[j] = b[order[std::size_t(s.first + j)]];
    const Eigen::VectorXd yz = solveSide(s, CHOLMOD_L, rhs);
    y[k] = yz.head(s.count);
    u[k] = yz.tail(ns);
    dtrmv_("L", "N", "N", &ns, s.T.data(), &ns, u[k].data(), &one, 1, 1, 1);
  });
  // Separator: L₃₃ y₃ = b₃ − L₃₁y₁ − L₃₂y₂, L₃₃ᵀ x₃ = y₃.
  Eigen::VectorXd x3(ns);
  for (int j = 0; j < ns; ++j) x3[j] = b[order[std::size_t(sepFirst + j)]] + u[0][j] + u[1][j];
  dtrsv_("L", "N", "N", &ns, f.L33.data(), &ns, x3.data(), &one, 1, 1, 1);
  dtrsv_("L", "T", "N", &ns, f.L33.data(), &ns, x3.data(), &one, 1, 1, 1);
  // Backward: side k solves L⁽ᵏ⁾ᵀ [x_k; q] = [y_k; T_kᵀ x₃] (then q = x₃, unused).
  Eigen::VectorXd x(n);
  for (int j = 0; j < ns; ++j) x[order[std::size_t(sepFirst + j)]] = x3[j];
  onBothSides(f.parallel, [&](int k) {
    Side& s = side[k];
    Eigen::VectorXd rhs(s.count + ns);
    rhs.head(s.count) = y[k];
    rhs.tail(ns) = x3;
    dtrmv_("L", "T", "N", &ns, s.T.data(), &ns, rhs.data() + s.count, &one, 1, 1, 1);
    const Eigen::VectorXd xq = solveSide(s, CHOLMOD_Lt, rhs);
    for (int j = 0; j < s.count; ++j) x[order[std::size_t(s.first + j)]] = xq[j];
  });
  return x;
}

Eigen::VectorXd splitCholeskySolve(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order,
                                   const std::vector<int>& position, int lower, int upper, const Eigen::VectorXd& b,
                                   SplitCholeskyStats* stats) {
  ABLMG_REQUIRE(b.size() == A.rows(),
                "splitCholeskySolve: right-hand side of " << b.size() << " entries for " << A.rows() << " unknowns");
  SplitCholesky factor(A, order, position, lower, upper, stats);
  const Stopwatch watch;
  Eigen::VectorXd x = factor.solve(b);
  if (stats) stats->solveSeconds = watch.seconds();
  return x;
}

}  // namespace ablmg::fem
