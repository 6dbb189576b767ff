// Fuzzes the parametric surface expressions of `ablmg surface` (mesher/surface.hpp):
// makeExpressionSurface from three newline-separated muparser expressions x(u,v), y(u,v),
// z(u,v), over [0,1]² or over the rectangle "u0 v0 u1 v1" of an optional fourth line. The
// header's promises are fuzzed: a bad expression or rectangle is an InputError; point(uv) is
// finite or an InputError; InducedMetricField::at (eq. 16) is an SPD metric or an InputError,
// "never a NaN metric". Anything else (a non-SPD or non-finite metric returned, a crash, a
// sanitizer report, another exception type) is a finding.
#include "ablmg/core/error.hpp"
#include "ablmg/mesher/surface.hpp"

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string s(reinterpret_cast<const char*>(data), size);
  std::string e[4];
  std::size_t k = 0;
  for (char c : s) {
    if (c == '\n' && k < 3)
      ++k;
    else
      e[k] += c;
  }
  double r[4] = {0, 0, 1, 1};
  if (k == 3) {
    std::istringstream in(e[3]);
    for (double& v : r)
      if (!(in >> v)) return 0;
  }
  std::unique_ptr<ablmg::mesher::ParametricSurface> surface;
  try {
    surface = ablmg::mesher::makeExpressionSurface(e[0], e[1], e[2], r[0], r[1], r[2], r[3], "fuzz");
  } catch (const ablmg::InputError&) { return 0; }
  const auto [lo, hi] = surface->parameterDomain().boundingBox();
  const ablmg::Vec2 mid = (lo + hi) / 2;
  for (const double h : {1.0, 1e-3}) {
    const ablmg::mesher::InducedMetricField field(*surface, ablmg::mesher::isotropicMetric3(h));
    for (const ablmg::Vec2& uv : {lo, hi, mid, ablmg::Vec2(lo.x(), hi.y()), ablmg::Vec2(0.3 * lo + 0.7 * hi)}) {
      try {
        if (!surface->point(uv).allFinite()) __builtin_trap();
      } catch (const ablmg::InputError&) {}
      try {
        if (!field.at(uv).isSpd()) __builtin_trap();
      } catch (const ablmg::InputError&) {}
    }
  }
  return 0;
}
