// Fuzzes Triangle's .poly reader (io/poly.hpp): parsePoly on any bytes gives an InputError or
// a Domain of positive area whose loops are closed (≥ 3 points, one tag per segment); every
// InputError names the file ("fuzz:<line>: ..." or "fuzz: ..."). A crash, a sanitizer report or
// another exception is a finding.
#include "ablmg/core/error.hpp"
#include "ablmg/io/poly.hpp"

#include <cstdint>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ablmg::Domain d = ablmg::io::parsePoly(text, "fuzz");
    if (!(d.area() > 0)) __builtin_trap();
    for (const auto& loop : d.loops())
      if (loop.points.size() < 3 || (!loop.tags.empty() && loop.tags.size() != loop.points.size())) __builtin_trap();
    (void)d.contains({0.5, 0.5});
  } catch (const ablmg::InputError& e) {
    if (std::string_view(e.what()).substr(0, 5) != "fuzz:") __builtin_trap();
  }
  return 0;
}
