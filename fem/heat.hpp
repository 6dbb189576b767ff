#pragma once
/// The heat equation on one mesh:  u_t − ∇·(κ ∇u) = f  in Ω,  u = g on ∂Ω (all boundary
/// vertices), P1 in space, backward Euler or BDF2 in time, constant κ > 0.
///
///   backward Euler:  (M/Δt + K) u^(n+1) = M u^n / Δt + F^(n+1)
///   BDF2:            (3M/(2Δt) + K) u^(n+1) = M (4u^n − u^(n−1)) / (2Δt) + F^(n+1)
///
/// M, K the P1 mass and stiffness matrices (fem/p1_matrices.hpp), F_i = ∫ f(·, t^(n+1)) φ_i by
/// the degree-5 rule; the Dirichlet values g(·, t^(n+1)) are lifted out as in fem/assemble.hpp.
/// BDF2 needs u^(n−1) at the same Δt: the first step after setState() without a previous
/// state (or after a change of Δt) is a backward Euler step. Orders 1 and 2 in Δt
/// (tests/fem/test_heat.cpp measures them on a manufactured solution).
///
/// The matrix c M + K (c = 1/Δt or 3/(2Δt)) is factorised by CHOLMOD (supernodal LLᵀ, AMD
/// ordering) once and reused for every step with the same c; factorisations() counts them.
/// The mesh is fixed for the solver's life: after a remesh, build a new HeatSolver and give it
/// the transferred state (adapt/transfer.hpp), u^n and u^(n−1) both for BDF2.
/// Deterministic: the same bits for any thread count (BLAS pinned to one thread, the policy of
/// fem/cholmod_threads.hpp, fixBlasThreads).
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/transient_problems.hpp"

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <memory>
#include <optional>
#include <string>

namespace ablmg::fem {

enum class TimeScheme { BackwardEuler, BDF2 };
/// "euler" / "bdf2" ↔ TimeScheme; parse throws InputError naming the valid names.
TimeScheme parseTimeScheme(const std::string& name);
std::string toString(TimeScheme scheme);

struct HeatProblem {
  double kappa = 1;       ///< > 0
  SpaceTimeFn f;          ///< source; empty = 0
  SpaceTimeFn dirichlet;  ///< g(x, y, t) on every boundary vertex (required)
};

/// κ, f and u as the Dirichlet data of a library problem.
HeatProblem heatProblem(const TransientProblem& problem);

class HeatSolver {
 public:
  /// `mesh` valid, outlives the solver. InputError for κ ≤ 0 or no Dirichlet data.
  HeatSolver(const Mesh2& mesh, HeatProblem problem, TimeScheme scheme);
  ~HeatSolver();
  HeatSolver(HeatSolver&&) noexcept;
  HeatSolver& operator=(HeatSolver&&) noexcept;

  /// The state at time t: u^n, and for BDF2 optionally u^(n−1) at t − dtPrevious.
  void setState(double t, Eigen::VectorXd u, std::optional<Eigen::VectorXd> previous = std::nullopt,
                double dtPrevious = 0);
  /// One step of length dt > 0 (InputError otherwise): time() += dt.
  void step(double dt);

  double time() const { return t_; }
  const Eigen::VectorXd& u() const { return u_; }
  /// u^(n−1) (empty before the first step, unless given to setState).
  const Eigen::VectorXd& previous() const { return previous_; }
  double dtPrevious() const { return dtPrevious_; }
  int factorizations() const { return factorizations_; }
  double factorSeconds() const { return factorSeconds_; }  ///< wall time spent factorising

 private:
  struct Factor;
  void factorise(double c);
  const Mesh2* mesh_;
  HeatProblem problem_;
  TimeScheme scheme_;
  Eigen::SparseMatrix<double> M_, K_;
  std::vector<int> dofOfVertex_, vertexOfDof_;
  std::unique_ptr<Factor> factor_;
  double factorC_ = 0;
  int factorizations_ = 0;
  double factorSeconds_ = 0;
  double t_ = 0, dtPrevious_ = 0;
  Eigen::VectorXd u_, previous_;
};

}  // namespace ablmg::fem
