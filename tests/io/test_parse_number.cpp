// Tests of cli/parse_number.hpp (compiled into test_io by tests/cli/io_cli.cmake): the one rule
// for numbers on the command line, and errors that name the flag and quote the text.
#include "ablmg/cli/parse_number.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace ablmg;
using namespace ablmg::cli;

namespace {

std::string errorOf(auto&& f) {
  try {
    f();
  } catch (const InputError& e) { return e.what(); }
  return "";
}

TEST(ParseNumber, DecimalAndScientificForms) {
  EXPECT_EQ(parseNumber("0.5", "x"), 0.5);
  EXPECT_EQ(parseNumber("-2", "x"), -2.0);
  EXPECT_EQ(parseNumber("+3", "x"), 3.0);
  EXPECT_EQ(parseNumber("1e-3", "x"), 1e-3);
  EXPECT_EQ(parseNumber(".25", "x"), 0.25);
  EXPECT_EQ(parseNumber("1.3", "x"), 1.3);  // the nearest double, as strtod gives
}

TEST(ParseNumber, RefusesAnythingButOneWholeNumber) {
  for (const char* bad : {"", " 1", "1 ", "1x", "abc", "0x10", "1,5", "--1", "+", "nan", "NaN", "1e400", "-1e400"})
    EXPECT_EQ(errorOf([&] { parseNumber(bad, "remesh: -hmin"); }),
              std::string("remesh: -hmin: expected a number, got '") + bad + "'")
        << bad;
}

TEST(ParseNumber, InfinityOnlyWhereAllowed) {
  EXPECT_NE(errorOf([] { parseNumber("inf", "adapt: --hgrad"); }), "");
  EXPECT_NE(errorOf([] { parseNumber("infinity", "adapt: --hgrad"); }), "");
  EXPECT_EQ(parseNumber("inf", "adapt: --p", Infinity::Allowed), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parseNumber("infinity", "adapt: --p", Infinity::Allowed), std::numeric_limits<double>::infinity());
  EXPECT_NE(errorOf([] { parseNumber("nan", "adapt: --p", Infinity::Allowed); }), "");
}

TEST(ParsePositiveNumber, RefusesZeroNegativeAndInfinite) {
  EXPECT_EQ(parsePositiveNumber("0.07", "surface: --h"), 0.07);
  for (const char* bad : {"0", "-1", "inf", "nan", "1e-400x", ""})
    EXPECT_EQ(errorOf([&] { parsePositiveNumber(bad, "surface: --h"); }),
              std::string("surface: --h: expected a positive number, got '") + bad + "'")
        << bad;
}

TEST(ParseInteger, WholeNumbersInRange) {
  EXPECT_EQ(parseInteger("7", "x", 0, 10), 7);
  EXPECT_EQ(parseInteger("-1", "x", -1, 10), -1);
  EXPECT_EQ(parseInteger("+4", "x", 0, 10), 4);
  EXPECT_EQ(errorOf([] { parseInteger("1.5", "remesh: -v", -1, 10); }),
            "remesh: -v: expected an integer in [-1, 10], got '1.5'");
  EXPECT_EQ(errorOf([] { parseInteger("11", "remesh: -v", -1, 10); }),
            "remesh: -v: expected an integer in [-1, 10], got '11'");
  EXPECT_EQ(errorOf([] { parseInteger("1e3", "remesh: -v", -1, 10); }),
            "remesh: -v: expected an integer in [-1, 10], got '1e3'");
  const long long big = std::numeric_limits<long long>::max();
  EXPECT_EQ(errorOf([&] { parseInteger("-3", "mesh: --seed", 0, big); }),
            "mesh: --seed: expected an integer >= 0, got '-3'");
  EXPECT_NE(errorOf([&] { parseInteger("99999999999999999999", "mesh: --seed", 0, big); }), "");
}

TEST(ParseOnOff, OnOffAndNothingElse) {
  for (const char* on : {"on", "true", "1"}) EXPECT_TRUE(parseOnOff(on, "adapt: --vtu")) << on;
  for (const char* off : {"off", "false", "0"}) EXPECT_FALSE(parseOnOff(off, "adapt: --vtu")) << off;
  EXPECT_EQ(errorOf([] { parseOnOff("yes", "adapt: --vtu"); }), "adapt: --vtu: expected on or off, got 'yes'");
}

}  // namespace
