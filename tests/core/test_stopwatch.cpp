// Mirrors core/stopwatch.hpp: seconds() grows with the time slept, lap() restarts, ScopedTimer
// adds its scope's seconds to the total it was given (and accumulates over scopes).
#include "ablmg/core/stopwatch.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace ablmg {
namespace {

void sleepMs(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

TEST(Stopwatch, SecondsCountTheTimeSinceTheStart) {
  Stopwatch w;
  const double a = w.seconds();
  EXPECT_GE(a, 0.0);
  sleepMs(20);
  const double b = w.seconds();
  EXPECT_GE(b, a + 0.02);
}

TEST(Stopwatch, LapRestarts) {
  Stopwatch outer, w;
  sleepMs(200);
  const double first = w.lap();
  EXPECT_GE(first, 0.2);
  sleepMs(10);
  const double second = w.lap();
  EXPECT_GE(second, 0.01);
  EXPECT_LT(second, 0.2);  // without the restart it would include the first 200 ms
  EXPECT_GE(outer.seconds(), first + second);
}

TEST(ScopedTimer, AddsItsScopeToTheTotal) {
  double total = 1.0;
  {
    ScopedTimer t(total);
    sleepMs(10);
    EXPECT_EQ(total, 1.0);  // added only when the scope ends
  }
  EXPECT_GE(total, 1.01);
  const double once = total;
  {
    ScopedTimer t(total);
    sleepMs(10);
  }
  EXPECT_GE(total, once + 0.01);
}

}  // namespace
}  // namespace ablmg
