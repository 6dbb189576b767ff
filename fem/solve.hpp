#pragma once
/// Solving the assembled P1 Poisson system with CHOLMOD's Cholesky factorisation (supernodal,
/// or simplicial when the fronts are too small for BLAS to pay: fem/cholmod_threads.hpp,
/// configureFactorisation). From SolveOptions::splitMinUnknowns (20000) unknowns the two sides
/// of the ordering's first cut are factorised apart, on two threads, and joined through the
/// separator's Schur complement (fem/split_cholesky.hpp); below, one CHOLMOD factorisation
/// (Eigen::CholmodSupernodalLLT).
///
/// Fill-reducing ordering: by default our geometric nested dissection (fem/ordering.hpp) —
/// the unknowns are permuted before CHOLMOD sees them and CHOLMOD keeps that order — because
/// CHOLMOD's own METIS ordering costs more than the factorisation at 10⁶ unknowns. Measured
/// on this 2-core machine, uniform mesh, 10⁶ unknowns, OpenBLAS: ≈ 0.5 s ordering + 3 s
/// factorisation, against ≈ 7 s + 2.8 s with CHOLMOD's METIS and 0.6 s + 4.1 s with AMD.
/// Its cuts are chosen by separator size in the graph, so the flops follow N and not the
/// grading (≈ 10⁵ unknowns: 0.37, 1.03 and 0.05 GFlop on the uniform, wave-front and tanh-layer
/// meshes, where the longer-axis rule took 0.57, 1.69 and 504; bench/bench_solve_graded.cpp).
/// (CHOLMOD's supernodal kernels need an optimised BLAS: with Debian's reference BLAS the
/// factorisation is ≈ 4× slower. Install libopenblas0-pthread.)
///
/// Determinism: the same system gives the same bits for any OMP_NUM_THREADS /
/// OPENBLAS_NUM_THREADS — our OpenMP loops sum in a fixed order, the split factorisation does
/// the same operations on one thread or two, and every factorisation
/// runs OpenBLAS with 1 thread (its threaded dpotrf rounds differently per thread count, and
/// its thread pool spins on each of the supernodal factorisation's many small calls: on a
/// loaded machine that made the solve 10–100× slower; fem/cholmod_threads.hpp, fixBlasThreads).
/// With our ordering CHOLMOD gets the lower triangle of the permuted matrix and keeps our order
/// as it is (no etree postorder: same flops and factor non-zeros, no per-call transposes).
///
/// Errors (InputError, with the reason): the system is not SPD or is singular — κ ≤ 0, no
/// Dirichlet boundary (pure Neumann), a mesh piece without Dirichlet vertex (from assemble()),
/// or CHOLMOD reporting a non-positive pivot.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/assemble.hpp"
#include "ablmg/fem/ordering.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <Eigen/Core>

#include <memory>

namespace ablmg::fem {

enum class Ordering {
  GeometricNestedDissection,  ///< fem/ordering.hpp on LinearSystem::dofPoints (default)
  Metis,                      ///< METIS_NodeND on the matrix graph (fem/ordering.hpp)
  Cholmod                     ///< CHOLMOD's default choice (AMD, then METIS if fill is high)
};

struct SolveOptions {
  Ordering ordering = Ordering::GeometricNestedDissection;
  int leafSize = 500;                            ///< pieces this small are ordered by AMD (geometric ordering only)
  CutChoice cut = CutChoice::SmallestSeparator;  ///< geometric ordering only
  /// Geometric ordering, at least this many unknowns: the two sides of the first cut are
  /// factorised apart, on two threads when there are two (fem/split_cholesky.hpp); below,
  /// one CHOLMOD factorisation. Either way the result is the same for any thread count.
  int splitMinUnknowns = 20000;
};

struct SolveStats {
  double assemblySeconds = 0;    ///< wall time of assemble()
  double orderingSeconds = 0;    ///< wall time of our ordering (geometric or METIS) + permutation
  double solveSeconds = 0;       ///< wall time of ordering + factorisation + triangular solves
  double symbolicSeconds = 0;    ///< of which: the permuted matrix and CHOLMOD's symbolic analysis
  double numericSeconds = 0;     ///< of which: the numeric factorisation
  double triangularSeconds = 0;  ///< of which: the triangular solves (and the permutation of b, x)
  int unknowns = 0;              ///< free vertices (size of A)
  long nonZeros = 0;             ///< stored non-zeros of A (both halves)
  double factorNonZeros = 0;     ///< non-zeros of the Cholesky factor L (CHOLMOD's lnz)
  double factorFlops = 0;        ///< floating-point operations of the factorisation (CHOLMOD's fl)
  int dirichletVertices = 0;
  double residual = 0;  ///< ‖A x − b‖₂ / ‖b‖₂ of the computed solution (0 if b = 0)
};

struct PoissonSolution {
  Eigen::VectorXd u;  ///< per vertex, Dirichlet values included
  SolveStats stats;
};

/// The ordering and the Cholesky factor of an assembled system's A, kept to solve further
/// right-hand sides with the same matrix: the adaptive loop's unit-load dual has the primal's
/// A (same κ, same Dirichlet vertices) and another b. A solve with a kept factor gives the same
/// bits as solveSystem on a system with that A (the same order and factor).
class Factorisation {
 public:
  /// Orders and factorises system.A (a copy of A is kept, for sameMatrix and the residual).
  /// `stats` receives the ordering, symbolic and numeric fields and the counts. InputError as
  /// solveSystem.
  explicit Factorisation(const LinearSystem& system, const SolveOptions& options = {}, SolveStats* stats = nullptr);
  /// The same, taking A over (`points`: system.dofPoints, read for the geometric ordering only).
  Factorisation(Eigen::SparseMatrix<double>&& A, const std::vector<Vec2>& points, const SolveOptions& options = {},
                SolveStats* stats = nullptr);
  ~Factorisation();
  Factorisation(Factorisation&&) noexcept;
  Factorisation& operator=(Factorisation&&) noexcept;

  /// x with A x = b (b: one entry per unknown). `stats` (optional): triangularSeconds and the
  /// factor's counts.
  Eigen::VectorXd solve(const Eigen::VectorXd& b, SolveStats* stats = nullptr);
  /// Whether A is bitwise the factorised matrix (same size, pattern and values).
  bool sameMatrix(const Eigen::SparseMatrix<double>& A) const;
  const Eigen::SparseMatrix<double>& matrix() const;

  struct Impl;  ///< opaque (fem/solve.cpp; solveSystem uses it without copying A)

 private:
  std::unique_ptr<Impl> impl_;
};

/// Solves A x = b of an assembled system. Returns x (free unknowns only).
/// `stats` (optional) receives the solve fields (not assemblySeconds / dirichletVertices).
Eigen::VectorXd solveSystem(const LinearSystem& system, SolveStats* stats = nullptr, const SolveOptions& options = {});

/// assemble() + solveSystem() + expand(): the P1 solution at every vertex of `mesh`.
PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem, const SolveOptions& options = {});

/// solvePoisson() with a factorisation kept across calls: when `factor` holds one of the
/// assembled A (bitwise: same mesh, κ and Dirichlet vertices, as the unit-load dual of the
/// problem last solved), only the triangular solves run (stats: orderingSeconds, symbolic and
/// numeric 0, the counts of the kept factor); otherwise A is factorised and `factor` replaced.
/// Same u, bit for bit, as solvePoisson(mesh, problem, options).
PoissonSolution solvePoisson(const Mesh2& mesh, const PoissonProblem& problem, const SolveOptions& options,
                             std::unique_ptr<Factorisation>& factor);

}  // namespace ablmg::fem
