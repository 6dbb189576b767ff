#pragma once
/// Sparse Cholesky solve of an SPD system whose two sides of a nested-dissection cut are
/// factorised apart, side by side on two threads (one level of George's block elimination;
/// A. George, "Nested dissection of a regular finite element mesh", SIAM J. Numer. Anal. 10,
/// 1973). In the order of the cut the unknowns are [side 1 (n₁), side 2 (n₂), separator (n_s)]:
///
///   M = [M₁₁ 0 M₁₃; 0 M₂₂ M₂₃; M₃₁ M₃₂ M₃₃]     (M₁₂ = 0: no edge crosses the separator)
///
/// Side k ∈ {1, 2} factorises its own SPD matrix [M_kk M_k3; M_3k M₃₃] with CHOLMOD (our order
/// kept, as fem/solve.cpp does for the whole matrix): its factor holds L_kk and L_3k of M's
/// factor, and a trailing dense T_k with T_k T_kᵀ = M₃₃ − L_3k L_3kᵀ. Then
///
///   S = M₃₃ − L₃₁L₃₁ᵀ − L₃₂L₃₂ᵀ = T₁T₁ᵀ + T₂T₂ᵀ − M₃₃,     L₃₃ = chol(S)   (LAPACK dpotrf)
///
/// and the solves run L and Lᵀ block by block (each side's by CHOLMOD, L₃₃'s by dtrsv).
/// The price: each side factorises the dense n_s × n_s block once more (n_s³/3 flops) and
/// forms T_k T_kᵀ (n_s³); on a 2-D mesh n_s ≈ √n, a few per cent of the flops at 10⁶ unknowns.
///
/// Deterministic: the two sides compute the same values on one thread or two (each side's
/// BLAS runs on the calling thread: fem/cholmod_threads.hpp), and S is summed in a fixed
/// order, so x is bitwise the same for any OMP_NUM_THREADS. InputError if M is not SPD.
#include <Eigen/Sparse>

#include <memory>
#include <vector>

namespace ablmg::fem {

struct SplitCholeskyStats {
  double symbolicSeconds = 0;  ///< wall time: the sides' matrices and CHOLMOD's analysis
  double numericSeconds = 0;   ///< wall time: the sides' factorisations, S and chol(S)
  double solveSeconds = 0;     ///< wall time: the triangular solves
  double factorNonZeros = 0;   ///< non-zeros of M's factor L (the dense block counted once)
  double factorFlops = 0;      ///< flops done (both sides' CHOLMOD counts + forming S + chol(S))
};

/// The factorisation of A in the order of a cut, kept for any number of right-hand sides.
/// `A`: n × n SPD (both halves stored, compressed); `order`: a permutation (order[k] = the
/// unknown placed k-th) whose first n₁ = `lower` and next n₂ = `upper` unknowns are the two
/// sides of a cut (no entry of A joins them), the rest its separator (n₁, n₂ ≥ 1,
/// n_s = n − n₁ − n₂ ≥ 1); `position` its inverse. Both are copied. The constructor
/// factorises (`stats`: symbolic, numeric and the counts); InputError if A is not SPD.
class SplitCholesky {
 public:
  SplitCholesky(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order, const std::vector<int>& position,
                int lower, int upper, SplitCholeskyStats* stats = nullptr);
  ~SplitCholesky();  ///< each side's factor is freed on its own thread
  SplitCholesky(const SplitCholesky&) = delete;
  SplitCholesky& operator=(const SplitCholesky&) = delete;

  /// x with A x = b, in A's numbering (b: n entries). The same bits for any thread count.
  Eigen::VectorXd solve(const Eigen::VectorXd& b);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// SplitCholesky(A, …) then solve(b): x with A x = b in A's numbering (stats->solveSeconds:
/// the triangular solves).
Eigen::VectorXd splitCholeskySolve(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order,
                                   const std::vector<int>& position, int lower, int upper, const Eigen::VectorXd& b,
                                   SplitCholeskyStats* stats = nullptr);

}  // namespace ablmg::fem
