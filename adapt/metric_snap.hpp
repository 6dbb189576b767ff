#pragma once
/// A metric made independent of round-off: each tensor snapped to a fixed grid in its
/// eigen-decomposition, so that two metrics that differ by round-off (a parallel solver's, a
/// reordering's: ~1e−11 relative) give the same bits, hence the same mesh.
///
/// Why: the bubble placement is chaotic in its input. A change of 1e−11 in one tensor moves the
/// whole packing to another of the same statistics, and the errors of a P1 solve on it then
/// differ by the method's mesh-to-mesh scatter (several % on the L-shape at 10³–10⁴ vertices,
/// docs/benchmarks.md "Mesh-to-mesh scatter"), which hides what a comparison of two solvers or
/// of 1 and 2 MPI ranks is after.
///
/// M = R(θ) diag(λ1, λ2) R(θ)ᵀ with λ1 ≥ λ2 > 0 becomes R(θ') diag(λ1', λ2') R(θ')ᵀ where
/// log2 λ' is rounded to a multiple of `quantum` (relative steps of 2^quantum − 1 in λ) and θ'
/// to one of n = round(π/quantum) angles per half-turn (θ and θ ± π, the same tensor, give the
/// same θ'); equal λ1', λ2' give the exact isotropic tensor (θ is meaningless there). The sizes h = λ^(−1/2) change by at most
/// quantum·ln2/4 relative (quantum 2⁻⁸: 0.07 %), far below a recovered metric's own error.
///
/// Not a guarantee: two inputs still snap apart when they straddle a grid boundary, with a
/// probability per vertex of about δ·(λ1/λ2)/quantum (δ their relative difference; λ1/λ2 =
/// the squared anisotropy, as λ2 is computed from entries of size λ1): for δ = 1e−11,
/// anisotropy 10 and quantum 2⁻⁸, 3·10⁻⁷ per vertex, so a 10⁵-vertex metric changes bits
/// with probability ~3 % against 1 without it.
#include "ablmg/core/metric2.hpp"

#include <span>

namespace ablmg::adapt {

/// quantum > 0 (InputError otherwise). Deterministic: the same input bits, the same output.
Metric2 snapMetric(const Metric2& m, double quantum);
void snapMetrics(std::span<Metric2> metrics, double quantum);

}  // namespace ablmg::adapt
