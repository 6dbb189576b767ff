#include "ablmg/fem/small_blas.hpp"

#include <cmath>
#include <cstddef>

namespace ablmg::fem::smallblas {
namespace {

/// Column j of a column-major matrix with leading dimension ld.
inline const double* column(const double* M, int ld, int j) { return M + std::ptrdiff_t(j) * ld; }
inline double* column(double* M, int ld, int j) { return M + std::ptrdiff_t(j) * ld; }

}  // namespace

// Each inner loop runs down a column (unit stride), so that the compiler vectorises it.

void gemmNT(int m, int n, int k, const double* A, int lda, const double* B, int ldb, double* C, int ldc) {
  for (int j = 0; j < n; ++j) {
    double* c = column(C, ldc, j);
    for (int i = 0; i < m; ++i) c[i] = 0;
    for (int p = 0; p < k; ++p) {
      const double* a = column(A, lda, p);
      const double b = column(B, ldb, p)[j];
      for (int i = 0; i < m; ++i) c[i] += a[i] * b;
    }
  }
}

void syrkLower(int n, int k, const double* A, int lda, double* C, int ldc) {
  for (int j = 0; j < n; ++j) {
    double* c = column(C, ldc, j);
    for (int i = j; i < n; ++i) c[i] = 0;
    for (int p = 0; p < k; ++p) {
      const double* a = column(A, lda, p);
      const double b = a[j];
      for (int i = j; i < n; ++i) c[i] += a[i] * b;
    }
  }
}

void trsmRightLowerT(int m, int n, const double* L, int ldl, double* B, int ldb) {
  // Column j of X = B L⁻ᵀ: X Lᵀ = B gives x_j = (b_j − Σ_{p<j} x_p L[j][p]) / L[j][j].
  for (int j = 0; j < n; ++j) {
    double* x = column(B, ldb, j);
    for (int p = 0; p < j; ++p) {
      const double l = column(L, ldl, p)[j];
      const double* xp = column(B, ldb, p);
      for (int i = 0; i < m; ++i) x[i] -= xp[i] * l;
    }
    const double inverse = 1.0 / column(L, ldl, j)[j];
    for (int i = 0; i < m; ++i) x[i] *= inverse;
  }
}

int potrfLower(int n, double* A, int lda) {
  // Left-looking, column by column (LAPACK's dpotf2 order).
  for (int j = 0; j < n; ++j) {
    double* a = column(A, lda, j);
    for (int p = 0; p < j; ++p) {
      const double* l = column(A, lda, p);
      const double ljp = l[j];
      for (int i = j; i < n; ++i) a[i] -= l[i] * ljp;
    }
    const double pivot = a[j];
    if (!(pivot > 0)) return j + 1;  // also NaN
    const double d = std::sqrt(pivot);
    a[j] = d;
    const double inverse = 1.0 / d;
    for (int i = j + 1; i < n; ++i) a[i] *= inverse;
  }
  return 0;
}

void trsvLower(bool transposed, int n, const double* L, int ldl, double* x) {
  if (!transposed) {  // forward: column j eliminates x_j from the rows below
    for (int j = 0; j < n; ++j) {
      const double* l = column(L, ldl, j);
      const double xj = x[j] / l[j];
      x[j] = xj;
      for (int i = j + 1; i < n; ++i) x[i] -= l[i] * xj;
    }
    return;
  }
  for (int j = n - 1; j >= 0; --j) {  // backward: row j of Lᵀ is column j of L
    const double* l = column(L, ldl, j);
    double s = x[j];
    for (int i = j + 1; i < n; ++i) s -= l[i] * x[i];
    x[j] = s / l[j];
  }
}

void gemvAdd(bool transposed, int m, int n, double alpha, const double* A, int lda, const double* x, double* y) {
  for (int j = 0; j < n; ++j) {
    const double* a = column(A, lda, j);
    if (!transposed) {
      const double xj = alpha * x[j];
      for (int i = 0; i < m; ++i) y[i] += a[i] * xj;
    } else {
      double s = 0;
      for (int i = 0; i < m; ++i) s += a[i] * x[i];
      y[j] += alpha * s;
    }
  }
}

}  // namespace ablmg::fem::smallblas
