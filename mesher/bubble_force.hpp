#pragma once
/// Inter-bubble force of paper §3.2, eq. (7)–(8); inline, tested alone.
///
/// Bubble size convention (core/metric2.hpp): the bubble of node i is the unit-metric ellipse
/// {v : vᵀ M_i v ≤ 1} scaled by 1/2, so the distance from x_i to its bubble boundary towards
/// x_j is l_ij = 0.5 · M_i.ellipseRadius(x_j − x_i), and two bubbles touch at the rest
/// distance l0 = l_ij + l_ji (eq. 8), ≈ 1 in metric units.
#include "ablmg/core/metric2.hpp"

#include <cmath>
#include <string>

namespace ablmg::mesher {

/// eq. (7): f(w) = k0 (1.25 w³ − 2.375 w² + 1.125) for 0 ≤ w ≤ 1.5, else 0. Positive =
/// repulsive (w < 1), zero at w = 1, negative = attractive (1 < w < 1.5), f(1.5) = 0.
inline double interBubbleForce(double w, double k0 = 1.0) {
  if (w < 0 || w > 1.5) return 0.0;
  return k0 * ((1.25 * w - 2.375) * w * w + 1.125);
}

/// w, the pair's distance in units of its rest length, from a² = |d|²_{M_i} and b² = |d|²_{M_j}.
/// Eq. (8) (the default, the paper's force): w = l / (l_ij + l_ji) = 2ab/(a + b), the harmonic
/// mean. The option: the eq. (3) length with the averaged tensor, w = √((a² + b²)/2). Both are
/// a + O((a − b)²) for a smooth metric, but where M jumps the harmonic mean follows the coarse
/// node: at rest (w = 1) with b = 5a it leaves a = 0.6, b = 3 and an edge of eq. (3) length
/// 2.2, beyond the adjacency radius 1.7, so the connection has no link for it and repairs its
/// triangles. With the averaged w the packing rests where the mesh is measured (quality.hpp).
/// Averaged suits metrics with jumps (fewer repaired triangles on an ungraded layer metric) but
/// raises the adaptive layer's H1 error by 8–15 %, so eq. (8) is the default (docs/method.md).
enum class PairDistance {
  Harmonic,  ///< 2ab/(a + b), eq. (8): l / (l_ij + l_ji) (default)
  Averaged,  ///< √((a² + b²)/2), eq. (3) with the averaged tensor
};
/// w from a² and b² (see above); a², b² > 0.
inline double pairDistance(double a2, double b2, PairDistance kind = PairDistance::Harmonic) {
  if (kind == PairDistance::Harmonic) {
    const double a = std::sqrt(a2), b = std::sqrt(b2);
    return 2.0 * a * b / (a + b);
  }
  return std::sqrt(0.5 * (a2 + b2));
}
/// "eq8" / "averaged" ↔ PairDistance; parse throws InputError naming the valid names.
PairDistance parsePairDistance(const std::string& name);
const char* pairDistanceName(PairDistance kind);

/// l_ij of eq. (8): distance (coordinate units) from x_i to the boundary of bubble i along d = x_j − x_i ≠ 0.
inline double bubbleRadius(const Metric2& mi, const Vec2& d) { return 0.5 * mi.ellipseRadius(d); }

/// l0 = l_ij + l_ji of eq. (8), coordinate units.
inline double restLength(double lij, double lji) { return lij + lji; }

}  // namespace ablmg::mesher
