#pragma once
/// Convergence rates: least-squares slope of log(error) against log(N) over the last k points.
/// For P1 on optimal meshes, the L2 error ~ N^(−1) and the H1 error ~ N^(−1/2) (slopes −1, −1/2).
#include <span>

namespace ablmg::adapt {

/// Slope s of the least-squares line log e = s log n + c through the last `lastK` pairs (all
/// if lastK ≤ 0 or larger than the size). Needs ≥ 2 pairs with n, e > 0 and two distinct n
/// (InputError otherwise, naming the offending index and value).
double logLogSlope(std::span<const double> n, std::span<const double> e, int lastK = 0);

/// Where an error curve (n[i], e[i]), in cycle order, first reaches `target`: the N at which
/// the piecewise-linear interpolation in log–log coordinates first falls to ≤ target (the
/// adaptive run's cost for, e.g., the finest uniform mesh's error). n[0] if e[0] ≤ target
/// already (then an upper bound); NaN if no point reaches it. Points must be positive and
/// finite (InputError naming the index otherwise).
double verticesToReach(std::span<const double> n, std::span<const double> e, double target);

}  // namespace ablmg::adapt
