// Fuzzes the medit .sol reader (io/medit.hpp): parseSol on any bytes, without and with an
// expected vertex count, gives an InputError or metrics that are every one SPD (Metric2::isSpd:
// finite, positive eigenvalues with finite inverses). A non-SPD metric returned without an
// error, an error that does not name the file ("fuzz:<line>: ..."), a crash or a sanitizer
// report is a finding.
#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace {
void check(const std::string& text, int expected) {
  try {
    const auto ms = ablmg::io::parseSol(text, "fuzz", expected);
    if (expected >= 0 && long(ms.size()) != expected) __builtin_trap();
    for (const auto& m : ms)
      if (!m.isSpd()) __builtin_trap();
  } catch (const ablmg::InputError& e) {
    if (std::string_view(e.what()).substr(0, 5) != "fuzz:") __builtin_trap();
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  check(text, -1);
  check(text, int(size % 8));  // a count the file may or may not have
  return 0;
}
