#pragma once
/// Inter-bubble force of paper §3.2, eq. (7)–(8); inline, tested alone.
///
/// Bubble size convention (core/metric2.hpp): the bubble of node i is the unit-metric ellipse
/// {v : vᵀ M_i v ≤ 1} scaled by 1/2, so the distance from x_i to its bubble boundary towards
/// x_j is l_ij = 0.5 · M_i.ellipseRadius(x_j − x_i), and two bubbles touch at the rest
/// distance l0 = l_ij + l_ji (eq. 8), ≈ 1 in metric units.
#include "core/metric2.hpp"

namespace ablmg::mesher {

/// eq. (7): f(w) = k0 (1.25 w³ − 2.375 w² + 1.125) for 0 ≤ w ≤ 1.5, else 0. Positive =
/// repulsive (w < 1), zero at w = 1, negative = attractive (1 < w < 1.5), f(1.5) = 0.
inline double interBubbleForce(double w, double k0 = 1.0) {
  if (w < 0 || w > 1.5) return 0.0;
  return k0 * ((1.25 * w - 2.375) * w * w + 1.125);
}

/// l_ij of eq. (8): distance (coordinate units) from x_i to the boundary of bubble i along d = x_j − x_i ≠ 0.
inline double bubbleRadius(const Metric2& mi, const Vec2& d) { return 0.5 * mi.ellipseRadius(d); }

/// l0 = l_ij + l_ji of eq. (8), coordinate units.
inline double restLength(double lij, double lji) { return lij + lji; }

} // namespace ablmg::mesher
