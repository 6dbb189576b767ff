// Fuzzes the JSON configuration of `ablmg mesh` (cli/config.hpp): parseConfig on any bytes
// gives an InputError or a Config whose domain has positive area and whose metric, evaluated at
// a few points, is SPD or an InputError; its options print and read back to the same JSON
// (meshOptionsToJson → applyMeshOptions). Anything else is a finding.
//
// The harness reads no file a config could name outside the fixtures: inputs whose string
// values contain '/' or ".." are skipped, and relative names resolve in tests/data (the small
// real .poly/.mesh/.sol fixtures, ABLMG_FUZZ_FILES_DIR), so "square_hole.poly" or
// {"mesh": "square.mesh", "sol": "square.sol"} are read, as `ablmg mesh` would read them.
#include "ablmg/cli/config.hpp"
#include "ablmg/core/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace {

using nlohmann::json;

/// False for inputs the harness does not run: strings that could name a file outside the
/// fixtures, and disk "samples" above 10⁵. The config accepts up to 10⁷ samples (legal), but
/// building and validating such a Domain takes seconds and 10⁹ bytes, which libFuzzer would
/// report as a timeout or an out-of-memory without any bug behind it.
bool acceptable(const json& j) {
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    return s.find('/') == std::string::npos && s.find("..") == std::string::npos;
  }
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "samples" && it.value().is_number() && !(it.value().get<double>() <= 1e5)) return false;
      if (!acceptable(it.value())) return false;
    }
  }
  if (j.is_array())
    for (const auto& v : j)
      if (!acceptable(v)) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const json pre = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!pre.is_discarded() && !acceptable(pre)) return 0;
  try {
    const ablmg::cli::Config c = ablmg::cli::parseConfig(text, "fuzz.json", ABLMG_FUZZ_FILES_DIR);
    if (!(c.domain.area() > 0) || !c.metric) __builtin_trap();
    const auto [lo, hi] = c.domain.boundingBox();
    for (const ablmg::Vec2& p : {lo, hi, ablmg::Vec2((lo + hi) / 2), c.domain.outer().points.front()}) {
      try {
        if (!c.metric->at(p).isSpd()) __builtin_trap();
      } catch (const ablmg::InputError&) {}
    }
    const json printed = ablmg::cli::meshOptionsToJson(c.options);
    ablmg::mesher::MeshOptions again;
    ablmg::cli::applyMeshOptions(printed, again, "fuzz.json: options");
    if (ablmg::cli::meshOptionsToJson(again) != printed) __builtin_trap();
  } catch (const ablmg::InputError&) {}
  return 0;
}
