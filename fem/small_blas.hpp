#pragma once
/// Dense kernels for the small blocks of a supernodal Cholesky factorisation and its solves:
/// the six BLAS/LAPACK operations CHOLMOD calls once or more per supernode (cholmod_super_numeric,
/// cholmod_super_lsolve/ltsolve), written as plain loops for blocks of at most kSmallWork
/// multiply-adds. Column-major, leading dimensions as in BLAS; every routine writes what the
/// BLAS routine of the same operation writes and nothing else.
///
/// Why: a 2-D P1 matrix's supernodes are small. The uniform 10⁵-unknown grid's factorisation is
/// ≈ 7·10⁴ BLAS calls per solve, most under 4096 multiply-adds, and OpenBLAS spends ≈ 1.2 µs in
/// each before any arithmetic (its buffer allocator's mutex, the level-3 driver's packing):
/// 0.05 s of the 0.06 s numeric phase for 0.35 GFlop. fem/cholmod_threads.hpp routes CHOLMOD's
/// calls of these shapes and sizes here inside a CholmodScope; larger blocks go to the BLAS,
/// whose blocked kernels win there. Measured in docs/experiments.md ("CHOLMOD's small BLAS calls").
///
/// Deterministic: fixed loop orders, no threads; the same inputs give the same bits.

namespace ablmg::fem::smallblas {

/// Blocks up to this many multiply-adds take the loops below (the BLAS above it).
inline constexpr long kSmallWork = 4096;

/// C = A Bᵀ: C m × n, A m × k, B n × k (BLAS dgemm "N", "T", α = 1, β = 0).
void gemmNT(int m, int n, int k, const double* A, int lda, const double* B, int ldb, double* C, int ldc);

/// lower(C) = lower(A Aᵀ): C n × n, A n × k; C's strict upper part untouched (dsyrk "L", "N",
/// α = 1, β = 0).
void syrkLower(int n, int k, const double* A, int lda, double* C, int ldc);

/// B := B L⁻ᵀ: B m × n, L n × n lower triangular with a non-zero diagonal (dtrsm "R", "L",
/// "T", "N", α = 1).
void trsmRightLowerT(int m, int n, const double* L, int ldl, double* B, int ldb);

/// A's lower triangle := L with L Lᵀ = A (A n × n SPD; its strict upper part untouched).
/// Returns 0, or j + 1 when the j-th pivot (0-based) is not positive, A's columns before j then
/// factorised and the rest partly updated (LAPACK dpotrf "L"'s info).
int potrfLower(int n, double* A, int lda);

/// x := L⁻¹ x (transposed: x := L⁻ᵀ x); L n × n lower, non-unit diagonal (dtrsv "L", "N"/"T",
/// "N", unit stride).
void trsvLower(bool transposed, int n, const double* L, int ldl, double* x);

/// y += α A x (transposed: y += α Aᵀ x); A m × n, unit strides (dgemv, β = 1).
void gemvAdd(bool transposed, int m, int n, double alpha, const double* A, int lda, const double* x, double* y);

}  // namespace ablmg::fem::smallblas
