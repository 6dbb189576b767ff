#pragma once
/// Quadrature rules on a triangle, in barycentric coordinates.
///
/// A rule of degree d integrates every polynomial of total degree ≤ d exactly:
///   ∫_T p dx = |T| · Σ_q w_q p(x_q),   x_q = Σ_k λ_{q,k} v_k,   Σ_q w_q = 1.
/// Weights are normalised to the triangle's area (they sum to 1); all are positive and
/// all points lie strictly inside the triangle (so singular integrands at vertices are safe).
///
/// Rules available (the smallest one of degree ≥ the request is returned):
///   degree 1: centroid, 1 point;
///   degree 2: 3 interior points (1/6, 1/6, 2/3), Strang & Fix (1973);
///   degree 5: 7 points, Radon / Strang & Fix (1973) table 4.1;
///   degree 8: 16 points, D. A. Dunavant, "High degree efficient symmetrical Gaussian
///             quadrature rules for the triangle", IJNME 21 (1985) 1129–1148.
#include <array>
#include <vector>

namespace ablmg::fem {

struct TriangleRule {
  int degree = 0;                             ///< polynomial degree integrated exactly
  std::vector<std::array<double, 3>> points;  ///< barycentric coordinates (λ0, λ1, λ2)
  std::vector<double> weights;                ///< sum to 1; multiply by |T|
  int size() const { return int(weights.size()); }
};

/// The smallest built-in rule exact for total degree ≥ `degree` (1 ≤ degree ≤ 8).
/// Throws InputError for degree outside [1, 8]. The reference is to a static object.
const TriangleRule& triangleRule(int degree);

/// Gauss–Legendre rule on [0, 1] with `n` points (1 ≤ n ≤ 3; exact to degree 2n − 1), for
/// edge (Neumann) integrals. Returns {abscissa t ∈ (0,1), weight} pairs; weights sum to 1.
const std::vector<std::array<double, 2>>& gaussLegendre01(int n);

}  // namespace ablmg::fem
