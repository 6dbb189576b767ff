// Mirrors core/parallel_failure.hpp: an exception thrown at index k inside a parallel loop of
// 2 threads is rethrown after the region (not std::terminate), the one of the lowest index when
// several throw (even when a higher one throws first in time), and the other iterations run.
#include "ablmg/core/parallel_failure.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ablmg/core/error.hpp"

namespace ablmg {
namespace {

constexpr int kN = 100;

/// y[i] = i + 1 for every i, except those in `throwing` which throw InputError("at <i>");
/// the lowest throwing index waits (bounded) until another failure was recorded, so the
/// winner is chosen by index, not by time.
std::vector<int> loop(const std::vector<int>& throwing, ParallelFailure& failure) {
  std::vector<int> y(kN, 0);
#pragma omp parallel for schedule(static) num_threads(2)
  for (int i = 0; i < kN; ++i)
    failure.run(i, [&] {
      for (std::size_t k = 0; k < throwing.size(); ++k) {
        if (throwing[k] != i) continue;
        if (k == 0 && throwing.size() > 1 && omp_get_num_threads() > 1) {
          const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
          while (!failure.failed() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        }
        ABLMG_REQUIRE(false, "at " << i);
      }
      y[std::size_t(i)] = i + 1;
    });
  return y;
}

TEST(ParallelFailure, NothingThrownNothingRethrown) {
  ParallelFailure failure;
  const auto y = loop({}, failure);
  EXPECT_FALSE(failure.failed());
  EXPECT_NO_THROW(failure.rethrow());
  for (int i = 0; i < kN; ++i) EXPECT_EQ(y[std::size_t(i)], i + 1);
}

TEST(ParallelFailure, OneThrowIsRethrownAfterTheRegion) {
  ParallelFailure failure;
  const auto y = loop({73}, failure);
  EXPECT_TRUE(failure.failed());
  EXPECT_EQ(failure.index(), 73);
  try {
    failure.rethrow();
    ADD_FAILURE() << "nothing rethrown";
  } catch (const InputError& e) { EXPECT_EQ(std::string(e.what()), "at 73"); }
  for (int i = 0; i < kN; ++i) EXPECT_EQ(y[std::size_t(i)], i == 73 ? 0 : i + 1);
}

TEST(ParallelFailure, TheLowestIndexWins) {
  // Index 10 (thread 0 of a static 2-thread schedule) throws after 90 and 60 (thread 1).
  ParallelFailure failure;
  const auto y = loop({10, 90, 60}, failure);
  EXPECT_EQ(failure.index(), 10);
  try {
    failure.rethrow();
    ADD_FAILURE() << "nothing rethrown";
  } catch (const InputError& e) { EXPECT_EQ(std::string(e.what()), "at 10"); }
  for (int i = 0; i < kN; ++i) EXPECT_EQ(y[std::size_t(i)], i == 10 || i == 60 || i == 90 ? 0 : i + 1);
}

TEST(ParallelFailure, RecordKeepsTheLowestIndexWhateverTheOrder) {
  ParallelFailure failure;
  failure.record(5, std::make_exception_ptr(std::runtime_error("five")));
  failure.record(2, std::make_exception_ptr(std::runtime_error("two")));
  failure.record(7, std::make_exception_ptr(std::runtime_error("seven")));
  EXPECT_EQ(failure.index(), 2);
  EXPECT_THROW(
      try { failure.rethrow(); } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "two");
        throw;
      },
      std::runtime_error);
}

}  // namespace
}  // namespace ablmg
