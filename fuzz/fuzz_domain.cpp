// Fuzzes Domain construction/validation with arbitrary coordinates (NaN, Inf, duplicates,
// self-intersections): InputError or a valid domain whose area is positive — never a crash.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/error.hpp"

#include <cstdint>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<double> v(size / sizeof(double));
  if (!v.empty()) std::memcpy(v.data(), data, v.size() * sizeof(double));
  if (v.size() < 6) return 0;
  const std::size_t nOuter = std::min<std::size_t>(v.size() / 2, 3 + (size % 7));
  ablmg::BoundaryLoop outer, hole;
  for (std::size_t k = 0; k < nOuter; ++k) outer.points.emplace_back(v[2 * k], v[2 * k + 1]);
  for (std::size_t k = nOuter; 2 * k + 1 < v.size(); ++k) hole.points.emplace_back(v[2 * k], v[2 * k + 1]);
  try {
    std::vector<ablmg::BoundaryLoop> holes;
    if (hole.points.size() >= 3) holes.push_back(hole);
    const ablmg::Domain d(outer, holes);
    if (!(d.area() > 0)) __builtin_trap();
    (void)d.contains({0.0, 0.0});
  } catch (const ablmg::InputError&) {}
  return 0;
}
