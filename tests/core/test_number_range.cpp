// The one reading of a number from text for every flag and setting.
#include <gtest/gtest.h>

#include <limits>

#include "hba/core/number_range.hpp"

namespace hba {
namespace {

const NumberRange kVoxel{0.01, 100, false, false, ""};
const NumberRange kWindow{2, std::numeric_limits<double>::infinity(), false, false, ""};
const NumberRange kOff{1e-3, 100, false, false, "off"};

std::string problem(const std::string& text, const NumberRange& range, NumberKind kind = NumberKind::Real) {
  return numberProblem(text, range, kind, rangeText(range));
}

TEST(NumberRange, RangesReadLikeTheDocs) {
  EXPECT_EQ(rangeText(kVoxel), "[0.01, 100]");
  EXPECT_EQ(rangeText(kWindow), ">= 2");
  EXPECT_EQ(rangeText(kOff), "0 (off) or [0.001, 100]");
  EXPECT_EQ(rangeText({0, 1, true, true, ""}), "(0, 1)");
  EXPECT_EQ(numberText(1e6), "1000000");
  EXPECT_EQ(numberText(0.1), "0.1");
}

TEST(NumberRange, GoodNumbersAreRead) {
  EXPECT_EQ(problem("2", kVoxel), "");
  EXPECT_EQ(problem("+0.5", kVoxel), "");
  EXPECT_EQ(problem("0", kOff), "");
  const ParsedNumber big = parseNumber("9007199254740993", {}, NumberKind::Count);
  ASSERT_TRUE(big.ok);
  EXPECT_EQ(big.whole, 9007199254740993LL);  // beyond a double's 53 bits, exact
  const ParsedNumber written = parseNumber("1e3", kWindow, NumberKind::Integer);
  ASSERT_TRUE(written.ok);
  EXPECT_EQ(written.whole, 1000);
}

TEST(NumberRange, BadNumbersSayWhy) {
  EXPECT_EQ(problem("inf", kVoxel), "must be [0.01, 100], got inf (not finite)");
  EXPECT_EQ(problem("nan", kVoxel), "must be [0.01, 100], got nan (not finite)");
  EXPECT_EQ(problem("-1", kVoxel), "must be [0.01, 100], got -1");
  EXPECT_EQ(problem("500", kVoxel), "must be [0.01, 100], got 500 (too large)");
  EXPECT_EQ(problem("1e400", kVoxel), "must be [0.01, 100], got 1e400 (too large)");
  EXPECT_EQ(problem("1e-400", kVoxel), "must be [0.01, 100], got 1e-400 (too close to 0)");
  EXPECT_EQ(problem("abc", kVoxel), "must be [0.01, 100], got abc (not a number)");
  EXPECT_EQ(problem("", kVoxel), "must be [0.01, 100], got  (not a number)");
  EXPECT_EQ(problem("0x10", kVoxel), "must be [0.01, 100], got 0x10 (not a number)");
  EXPECT_EQ(problem("1e-4", kOff), "must be 0 (off) or [0.001, 100], got 1e-4");
  EXPECT_EQ(problem("-3", kWindow, NumberKind::Integer), "must be >= 2, got -3");
  EXPECT_EQ(problem("2.5", kWindow, NumberKind::Integer), "must be >= 2, got 2.5 (not a whole number)");
  EXPECT_EQ(problem("99999999999999999999", kWindow, NumberKind::Integer),
            "must be >= 2, got 99999999999999999999 (too large: at most 2147483647)");
  EXPECT_EQ(problem("-99999999999999999999", kWindow, NumberKind::Integer),
            "must be >= 2, got -99999999999999999999 (too small)");
  EXPECT_EQ(problem("-1", {0, 10, false, false, ""}, NumberKind::Count),
            "must be [0, 10], got -1 (too small)");
}

}  // namespace
}  // namespace hba
