#include "ablmg/cli/parse_number.hpp"

#include "ablmg/core/error.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

namespace ablmg::cli {
namespace {

/// from_chars over the whole text (after one optional leading '+', which from_chars does not
/// take): true when every character was used.
template <class T>
bool readWhole(const std::string& text, T& value) {
  std::string_view s(text);
  if (s.size() > 1 && s[0] == '+' && (std::isdigit(static_cast<unsigned char>(s[1])) || s[1] == '.'))
    s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

double parseNumber(const std::string& text, const std::string& where, Infinity infinity) {
  double v = 0;
  const bool ok = readWhole(text, v) && !std::isnan(v) && (std::isfinite(v) || infinity == Infinity::Allowed);
  ABLMG_REQUIRE(ok, where << ": expected a number, got '" << text << "'");
  return v;
}

double parsePositiveNumber(const std::string& text, const std::string& where) {
  double v = 0;
  const bool ok = readWhole(text, v) && std::isfinite(v) && v > 0;
  ABLMG_REQUIRE(ok, where << ": expected a positive number, got '" << text << "'");
  return v;
}

long long parseInteger(const std::string& text, const std::string& where, long long lo, long long hi) {
  long long v = 0;
  const bool ok = readWhole(text, v) && v >= lo && v <= hi;
  if (hi == std::numeric_limits<long long>::max())
    ABLMG_REQUIRE(ok, where << ": expected an integer >= " << lo << ", got '" << text << "'");
  ABLMG_REQUIRE(ok, where << ": expected an integer in [" << lo << ", " << hi << "], got '" << text << "'");
  return v;
}

bool parseOnOff(const std::string& text, const std::string& where) {
  if (text == "on" || text == "true" || text == "1") return true;
  if (text == "off" || text == "false" || text == "0") return false;
  ABLMG_REQUIRE(false, where << ": expected on or off, got '" << text << "'");
  return false;
}

}  // namespace ablmg::cli
