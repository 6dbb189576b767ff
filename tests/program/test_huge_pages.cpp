// The ablmg program's operator new (cli/huge_pages.cpp): a block of 4 MB or more is eligible for
// transparent huge pages, a small one is left as it was, and new[] / delete pairs keep working.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string thpMode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(f, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

/// /proc/self/smaps' THPeligible flag of the mapping holding `address`; -1 when it is not found.
int thpEligible(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= a && a < end;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

TEST(HugePages, LargeBlocksAreEligibleAndSmallOnesAreNot) {
  if (thpMode() != "madvise") GTEST_SKIP() << "transparent huge pages are '" << thpMode() << "', not madvise";
  std::vector<double> large(std::size_t(1) << 20, 1.0);  // 8 MB
  EXPECT_EQ(thpEligible(large.data() + large.size() / 2), 1);
  auto small = std::make_unique<char[]>(std::size_t(64) << 10);  // 64 KB: glibc's heap
  EXPECT_EQ(thpEligible(small.get()), 0);
}

TEST(HugePages, EveryFormOfNewPairsWithItsDelete) {
  for (std::size_t bytes : {std::size_t(0), std::size_t(24), std::size_t(5) << 20}) {
    auto* array = new char[bytes + 1];
    array[bytes] = 7;
    delete[] array;
    auto* one = new (std::nothrow) std::vector<int>(bytes / sizeof(int), 3);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->size(), bytes / sizeof(int));
    delete one;
  }
}

}  // namespace
