#pragma once
/// Assembly of the continuous P1 discretisation of a PoissonProblem on a Mesh2.
///
/// Unknowns are the values at the non-Dirichlet vertices ("free" vertices, numbered in vertex
/// order). Dirichlet conditions are imposed by lifting: u = u_0 + g_h with g_h the nodal
/// interpolant of g_D on the Dirichlet vertices; the Dirichlet rows and columns are removed,
/// so the system A x = b is symmetric, and positive definite when κ > 0 and every connected
/// piece of the mesh touches the Dirichlet boundary (both checked, InputError otherwise).
///
///   A_ij = Σ_T (∫_T κ) ∇φ_i·∇φ_j   (∇φ constant on T; ∫_T κ exact for a constant or
///                                    per-vertex κ, by the degree-5 rule for a function;
///                                    κ of T's subdomain with PoissonProblem::kappaBySubdomain)
///   b_i  = ∫ f φ_i + ∫_{Γ_N} g_N φ_i − Σ_{j Dirichlet} A_ij g_j
/// f given as a function is integrated with the degree-5 rule (never interpolated: an
/// interpolated load spoils the error on steep solutions), g_N with 3-point Gauss on edges.
///
/// The sparsity pattern (vertex adjacency) is built directly in compressed form: O(N) memory
/// beyond the matrix, no triplet list.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <Eigen/Sparse>

#include <vector>

namespace ablmg::fem {

struct LinearSystem {
  Eigen::SparseMatrix<double> A;    ///< free × free, symmetric (both halves stored)
  Eigen::VectorXd b;                ///< free
  std::vector<int> dofOfVertex;     ///< −1 for Dirichlet vertices
  std::vector<int> vertexOfDof;     ///< inverse of dofOfVertex
  std::vector<Vec2> dofPoints;      ///< position of each unknown (for geometric orderings)
  Eigen::VectorXd dirichletValues;  ///< per vertex: g_D at Dirichlet vertices, 0 elsewhere
  int numDirichletVertices = 0;

  /// Full per-vertex solution from the free unknowns x (Dirichlet values filled in).
  Eigen::VectorXd expand(const Eigen::VectorXd& x) const;
};

/// Assembles the system. Throws InputError when: a per-vertex datum has the wrong size,
/// κ ≤ 0 or non-finite at a quadrature point (names the triangle and the value), no vertex
/// is Dirichlet or a connected piece of the mesh has none (the system would be singular).
LinearSystem assemble(const Mesh2& mesh, const PoissonProblem& problem);

/// Which vertices carry Dirichlet data and their values, per the rules of PoissonProblem
/// (a vertex shared by a Dirichlet and a Neumann edge is Dirichlet). Used by assemble().
/// Returns per-vertex flags; `values` receives g_D (0 at non-Dirichlet vertices).
std::vector<char> dirichletVertices(const Mesh2& mesh, const PoissonProblem& problem, Eigen::VectorXd& values);

}  // namespace ablmg::fem
