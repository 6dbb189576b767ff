#include "ablmg/adapt/convergence.hpp"

#include "ablmg/core/error.hpp"

#include <cmath>

namespace ablmg::adapt {

double logLogSlope(std::span<const double> n, std::span<const double> e, int lastK) {
  ABLMG_REQUIRE(n.size() == e.size(), "logLogSlope: " << n.size() << " abscissae for " << e.size() << " errors");
  const std::size_t size = n.size();
  const std::size_t k = (lastK <= 0 || std::size_t(lastK) > size) ? size : std::size_t(lastK);
  ABLMG_REQUIRE(k >= 2, "logLogSlope: needs at least 2 points (got " << k << ")");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = size - k; i < size; ++i) {
    ABLMG_REQUIRE(n[i] > 0 && e[i] > 0 && std::isfinite(n[i]) && std::isfinite(e[i]),
                  "logLogSlope: point " << i << " is not positive (n " << n[i] << ", error " << e[i] << ")");
    const double x = std::log(n[i]), y = std::log(e[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double kk = double(k);
  const double den = kk * sxx - sx * sx;
  ABLMG_REQUIRE(den > 1e-12 * kk * sxx, "logLogSlope: all N are equal");
  return (kk * sxy - sx * sy) / den;
}

double verticesToReach(std::span<const double> n, std::span<const double> e, double target) {
  ABLMG_REQUIRE(n.size() == e.size(), "verticesToReach: " << n.size() << " abscissae for " << e.size() << " errors");
  ABLMG_REQUIRE(target > 0 && std::isfinite(target), "verticesToReach: target " << target << " is not positive");
  for (std::size_t i = 0; i < n.size(); ++i)
    ABLMG_REQUIRE(n[i] > 0 && e[i] > 0 && std::isfinite(n[i]) && std::isfinite(e[i]),
                  "verticesToReach: point " << i << " is not positive (n " << n[i] << ", error " << e[i] << ")");
  if (!n.empty() && e[0] <= target) return n[0];
  for (std::size_t i = 1; i < n.size(); ++i) {
    if (e[i] > target) continue;
    // e[i−1] > target ≥ e[i]: interpolate log n linearly in log e.
    const double t = std::log(e[i - 1] / target) / std::log(e[i - 1] / e[i]);
    return std::exp(std::log(n[i - 1]) + t * std::log(n[i] / n[i - 1]));
  }
  return std::nan("");
}

}  // namespace ablmg::adapt
