#include "hba/core/memory_budget.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

namespace hba {
namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;

TEST(MemoryBudget, IsExceededOnceTheProcessGrowsBeyondIt) {
  if (!std::filesystem::exists("/proc/self/statm")) GTEST_SKIP() << "no /proc/self/statm";
  const MemoryBudget budget(8 * kMiB, "a test's");
  EXPECT_FALSE(budget.exceeded());
  EXPECT_TRUE(budget.exceeded(64 * kMiB));  // with what is still to come
  std::vector<char> grown(64 * kMiB, 1);    // touched: resident
  EXPECT_TRUE(budget.exceeded());
  const std::string message = budget.exceededBy("the test's buffer").what();
  EXPECT_NE(message.find("the test's buffer outgrew the memory available: it took"), std::string::npos)
      << message;
  EXPECT_NE(message.find("of the 8 MiB there were (a test's"), std::string::npos) << message;
  EXPECT_EQ(grown.back(), 1);
}

TEST(MemoryBudget, WithoutALimitIsNeverExceeded) {
  const MemoryBudget none;
  EXPECT_FALSE(none.limited());
  std::vector<char> grown(64 * kMiB, 1);
  EXPECT_FALSE(none.exceeded(std::size_t{1} << 50));
  EXPECT_EQ(grown.back(), 1);
}

TEST(MemoryBudget, OfTheMemoryAvailableEitherWayIsLimitedAndRoomy) {
  if (!std::filesystem::exists("/proc/meminfo")) GTEST_SKIP() << "no /proc/meminfo";
  for (const MemoryBudget& budget :
       {MemoryBudget::ofAvailableMemory(), MemoryBudget::ofAvailableMemoryAsHeld()}) {
    EXPECT_TRUE(budget.limited());
    EXPECT_FALSE(budget.exceeded(kMiB));                 // a machine that runs tests has a MiB free
    EXPECT_TRUE(budget.exceeded(std::size_t{1} << 60));  // and not an exabyte
  }
}

TEST(MemoryBudget, ResidentBytesAreKnownOnLinux) {
  if (!std::filesystem::exists("/proc/self/statm")) GTEST_SKIP() << "no /proc/self/statm";
  EXPECT_GT(residentBytes(), 0u);
}

}  // namespace
}  // namespace hba
