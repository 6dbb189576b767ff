#include "ablmg/adapt/metric_snap.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ablmg::adapt {

Metric2 snapMetric(const Metric2& m, double quantum) {
  const double a = m.m11(), b = m.m12(), c = m.m22();
  const double mean = 0.5 * (a + c), d = std::hypot(0.5 * (a - c), b);
  const double l1 = mean + d;
  const double l2 = std::max(mean - d, l1 * 1e-300);
  const auto snap = [quantum](double x) { return std::round(x / quantum) * quantum; };
  const double s1 = std::exp2(snap(std::log2(l1))), s2 = std::exp2(snap(std::log2(l2)));
  if (s1 == s2) return Metric2::raw(s1, 0.0, s1);
  // θ on a grid of n steps per half-turn, its index taken modulo n: θ and θ ± π (the same
  // tensor, e.g. a sign of m12 flipped by round-off near θ = ±π/2) snap to the same angle.
  const long long n = std::max(1LL, std::llround(std::numbers::pi / quantum));
  const double step = std::numbers::pi / double(n);
  const long long k = ((std::llround(0.5 * std::atan2(2 * b, a - c) / step) % n) + n) % n;
  const double theta = double(k) * step;
  const double cs = std::cos(theta), sn = std::sin(theta);
  return Metric2::raw(s1 * cs * cs + s2 * sn * sn, (s1 - s2) * cs * sn, s1 * sn * sn + s2 * cs * cs);
}

void snapMetrics(std::span<Metric2> metrics, double quantum) {
  ABLMG_REQUIRE(std::isfinite(quantum) && quantum > 0, "metric quantum must be > 0, got " << quantum);
  for (Metric2& m : metrics) m = snapMetric(m, quantum);
}

}  // namespace ablmg::adapt
