#include "ablmg/fem/cholmod_threads.hpp"

#include "ablmg/fem/small_blas.hpp"

#include <dlfcn.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>

namespace ablmg::fem {
namespace {

thread_local int scopeDepth = 0;        // CholmodScopes alive on this thread
thread_local long teamlessRegions = 0;  // regions run without a team on this thread

}  // namespace

CholmodScope::CholmodScope() : saved_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
  ++scopeDepth;
}

CholmodScope::~CholmodScope() {
  --scopeDepth;
  omp_set_max_active_levels(saved_);
}

long teamlessRegionCount() { return teamlessRegions; }

}  // namespace ablmg::fem

namespace {

/// The definition of `name` that this program's replaces (the next one in the lookup order:
/// the OpenMP runtime's, the BLAS's); aborts with a message if there is none.
template <class F>
F nextDefinition(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);
  if (!f) {
    std::fprintf(stderr, "ablmg: %s was not found after this program's definition (fem/cholmod_threads.cpp)\n", name);
    std::abort();
  }
  return reinterpret_cast<F>(f);
}

}  // namespace

/// libgomp's entry point for `#pragma omp parallel` (GCC's code, CHOLMOD's included, calls
/// it with the outlined body `fn`, its argument, the requested thread count and the
/// proc_bind flags). Defined here, it takes the calls of every library that the dynamic
/// linker resolves to this program (libcholmod.so among them): inside a CholmodScope on a
/// thread in no parallel region, the region's team would be one thread (max-active-levels
/// 0), and the body runs directly on the calling thread; every other call goes to the
/// runtime's own GOMP_parallel (the next definition in the lookup order: libgomp's, or
/// LLVM's libomp's compatible one). fem/cholmod_threads.hpp says why.
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned numThreads, unsigned flags) {
  using Entry = void (*)(void (*)(void*), void*, unsigned, unsigned);
  if (ablmg::fem::scopeDepth > 0 && omp_get_level() == 0) {
    ++ablmg::fem::teamlessRegions;
    fn(data);
    return;
  }
  static const Entry runtime = nextDefinition<Entry>("GOMP_parallel");
  runtime(fn, data, numThreads, flags);
}

// ---- CHOLMOD's small BLAS calls (fem/small_blas.hpp).
//
// Defined here, these BLAS/LAPACK entry points take the calls of every library that the
// dynamic linker resolves to this program, CHOLMOD's among them (as GOMP_parallel above).
// Inside a CholmodScope, a call of the shape CHOLMOD's supernodal factorisation and solves
// make, on a block of at most kSmallWork multiply-adds, runs the loops of fem/small_blas.cpp;
// every other call goes to the next definition in the lookup order (the BLAS CHOLMOD was
// linked with). The arguments are those of the Fortran interface, with the hidden lengths of
// the character arguments, which the loops do not read and the BLAS gets as they came.
namespace {

using ablmg::fem::smallblas::kSmallWork;

thread_local long smallCalls = 0;  // calls the loops took on this thread

/// A call inside a CholmodScope on a block of at most kSmallWork multiply-adds.
bool small(long work) { return ablmg::fem::scopeDepth > 0 && work <= kSmallWork; }

bool is(const char* flag, char c) { return *flag == c; }
bool transposed(const char* flag) { return *flag == 'T' || *flag == 'C'; }  // real: C = T

}  // namespace

namespace ablmg::fem {
long smallBlasCallCount() { return smallCalls; }
}  // namespace ablmg::fem

extern "C" {

void dgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const double* alpha,
            const double* A, const int* lda, const double* B, const int* ldb, const double* beta, double* C,
            const int* ldc, std::size_t lta, std::size_t ltb) {
  using Entry =
      void (*)(const char*, const char*, const int*, const int*, const int*, const double*, const double*, const int*,
               const double*, const int*, const double*, double*, const int*, std::size_t, std::size_t);
  if (is(ta, 'N') && transposed(tb) && *alpha == 1 && *beta == 0 && small(long(*m) * *n * *k)) {
    ++smallCalls;
    ablmg::fem::smallblas::gemmNT(*m, *n, *k, A, *lda, B, *ldb, C, *ldc);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dgemm_");
  blas(ta, tb, m, n, k, alpha, A, lda, B, ldb, beta, C, ldc, lta, ltb);
}

void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* A,
            const int* lda, const double* beta, double* C, const int* ldc, std::size_t lu, std::size_t lt) {
  using Entry = void (*)(const char*, const char*, const int*, const int*, const double*, const double*, const int*,
                         const double*, double*, const int*, std::size_t, std::size_t);
  if (is(uplo, 'L') && is(trans, 'N') && *alpha == 1 && *beta == 0 && small(long(*n) * (*n + 1) / 2 * *k)) {
    ++smallCalls;
    ablmg::fem::smallblas::syrkLower(*n, *k, A, *lda, C, *ldc);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dsyrk_");
  blas(uplo, trans, n, k, alpha, A, lda, beta, C, ldc, lu, lt);
}

void dtrsm_(const char* side, const char* uplo, const char* trans, const char* diag, const int* m, const int* n,
            const double* alpha, const double* A, const int* lda, double* B, const int* ldb, std::size_t ls,
            std::size_t lu, std::size_t lt, std::size_t ld) {
  using Entry =
      void (*)(const char*, const char*, const char*, const char*, const int*, const int*, const double*, const double*,
               const int*, double*, const int*, std::size_t, std::size_t, std::size_t, std::size_t);
  if (is(side, 'R') && is(uplo, 'L') && transposed(trans) && is(diag, 'N') && *alpha == 1 &&
      small(long(*m) * *n * (*n + 1) / 2)) {
    ++smallCalls;
    ablmg::fem::smallblas::trsmRightLowerT(*m, *n, A, *lda, B, *ldb);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dtrsm_");
  blas(side, uplo, trans, diag, m, n, alpha, A, lda, B, ldb, ls, lu, lt, ld);
}

void dpotrf_(const char* uplo, const int* n, double* A, const int* lda, int* info, std::size_t lu) {
  using Entry = void (*)(const char*, const int*, double*, const int*, int*, std::size_t);
  if (is(uplo, 'L') && *n >= 0 && *lda >= (*n > 1 ? *n : 1) && small(long(*n) * *n * *n / 6)) {
    ++smallCalls;
    *info = ablmg::fem::smallblas::potrfLower(*n, A, *lda);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dpotrf_");
  blas(uplo, n, A, lda, info, lu);
}

void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* A, const int* lda,
            double* x, const int* incx, std::size_t lu, std::size_t lt, std::size_t ld) {
  using Entry = void (*)(const char*, const char*, const char*, const int*, const double*, const int*, double*,
                         const int*, std::size_t, std::size_t, std::size_t);
  if (is(uplo, 'L') && is(diag, 'N') && (is(trans, 'N') || transposed(trans)) && *incx == 1 &&
      small(long(*n) * (*n + 1) / 2)) {
    ++smallCalls;
    ablmg::fem::smallblas::trsvLower(transposed(trans), *n, A, *lda, x);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dtrsv_");
  blas(uplo, trans, diag, n, A, lda, x, incx, lu, lt, ld);
}

void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* A, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy, std::size_t lt) {
  using Entry = void (*)(const char*, const int*, const int*, const double*, const double*, const int*, const double*,
                         const int*, const double*, double*, const int*, std::size_t);
  if ((is(trans, 'N') || transposed(trans)) && *incx == 1 && *incy == 1 && *beta == 1 && small(long(*m) * *n)) {
    ++smallCalls;
    ablmg::fem::smallblas::gemvAdd(transposed(trans), *m, *n, *alpha, A, *lda, x, y);
    return;
  }
  static const Entry blas = nextDefinition<Entry>("dgemv_");
  blas(trans, m, n, alpha, A, lda, x, incx, beta, y, incy, lt);
}

}  // extern "C"
