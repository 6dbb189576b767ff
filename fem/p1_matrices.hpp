#pragma once
/// The P1 mass and stiffness matrices of a Mesh2, over every vertex (no boundary condition),
/// for time stepping (fem/heat.hpp) and solution transfer (adapt/transfer.hpp).
///
///   M_ij = ∫ φ_i φ_j  = Σ_T |T| (1 + δ_ij) / 12          (exact)
///   K_ij = ∫ κ ∇φ_i·∇φ_j = Σ_T κ |T| ∇λ_i·∇λ_j             (κ > 0 constant)
///
/// Both N × N, symmetric, both halves stored, on the same sparsity pattern (the vertex
/// adjacency plus the diagonal), built in compressed form without a triplet list: each
/// triangle's nine entries are written through precomputed slots (P1Pattern), in triangle
/// order, so the values are bitwise reproducible.
#include "ablmg/core/mesh2.hpp"

#include <Eigen/Sparse>

#include <array>
#include <vector>

namespace ablmg::fem {

struct P1Pattern {
  Eigen::SparseMatrix<double> matrix;     ///< the pattern, values 0
  std::vector<std::array<int, 9>> slots;  ///< per triangle: index into valuePtr() of entry (a, b), a, b ∈ 0..2, 3a + b
};

/// The pattern of a valid mesh (every vertex in a triangle).
P1Pattern p1Pattern(const Mesh2& mesh);

/// Consistent mass matrix M.
Eigen::SparseMatrix<double> massMatrix(const Mesh2& mesh);
Eigen::SparseMatrix<double> massMatrix(const Mesh2& mesh, const P1Pattern& pattern);

/// Stiffness matrix K with constant κ > 0 (InputError otherwise).
Eigen::SparseMatrix<double> stiffnessMatrix(const Mesh2& mesh, double kappa);
Eigen::SparseMatrix<double> stiffnessMatrix(const Mesh2& mesh, const P1Pattern& pattern, double kappa);

/// Lumped masses m_i = ∫ φ_i = Σ_{T∋i} |T| / 3 (the row sums of M).
Eigen::VectorXd lumpedMass(const Mesh2& mesh);

}  // namespace ablmg::fem
