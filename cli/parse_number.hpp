#pragma once
/// Numbers (and on/off switches) on the command line: one rule for every `ablmg` command.
///
/// The whole argument is one number in C's decimal or scientific form ("0.5", "-2", "1e-3",
/// an optional leading '+'); no surrounding blanks, no trailing text, no hexadecimal. NaN and
/// values beyond a double's range are refused; "inf" / "infinity" only where a flag means
/// infinity (Infinity::Allowed: `adapt --p inf`, `adapt --hmax inf`). Integers are whole
/// numbers without a fraction or exponent, within [lo, hi].
///
/// Errors are ablmg::InputError naming the flag and quoting the text, e.g.
/// "remesh: -hmin: expected a number, got 'abc'".
#include <string>

namespace ablmg::cli {

enum class Infinity { Refused, Allowed };

/// A finite number (or ±∞ with Infinity::Allowed).
double parseNumber(const std::string& text, const std::string& where, Infinity infinity = Infinity::Refused);
/// A finite number > 0.
double parsePositiveNumber(const std::string& text, const std::string& where);
/// An integer in [lo, hi].
long long parseInteger(const std::string& text, const std::string& where, long long lo, long long hi);
/// A switch: on / true / 1 or off / false / 0 ("<where>: expected on or off, got '<text>'").
bool parseOnOff(const std::string& text, const std::string& where);

}  // namespace ablmg::cli
