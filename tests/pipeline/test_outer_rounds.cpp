// --iterations is a maximum: the rounds stop when the poses settle or when
// their moves stop shrinking (src/pipeline/outer_rounds.hpp).
#include <gtest/gtest.h>

#include "hba/settings/settings.hpp"
#include "pipeline/outer_rounds.hpp"

namespace hba::pipeline {
namespace {

HbaSettings withRounds(int rounds) {
  HbaSettings settings;  // settle tolerances 0.01 m and 0.01 deg
  settings.outer_iterations = rounds;
  return settings;
}

TEST(OuterRounds, ASmallRoundSettlesThePoses) {
  const HbaSettings settings = withRounds(50);
  OuterRounds rounds(settings);
  EXPECT_FALSE(rounds.stopAfter(1, {0.5, 1.0}));
  EXPECT_FALSE(rounds.stopAfter(2, {0.05, 0.02}));
  EXPECT_TRUE(rounds.stopAfter(3, {0.004, 0.002}));
  EXPECT_EQ(rounds.why(), RoundsStop::Settled);
  EXPECT_EQ(rounds.reason(),
            "settled after 3 rounds: largest move 0.0040 m, 0.0020 deg (within 0.01 m, 0.01 deg)");
  EXPECT_STREQ(toString(rounds.why()), "poses settled");
}

// Both tolerances: a round that moved little but turned much is no settle.
TEST(OuterRounds, BothTolerancesMustHold) {
  const HbaSettings settings = withRounds(50);
  OuterRounds rounds(settings);
  EXPECT_FALSE(rounds.stopAfter(1, {0.001, 0.5}));
  EXPECT_FALSE(rounds.stopAfter(2, {0.2, 0.001}));  // 20 tolerances after 50: still shrinking
  EXPECT_TRUE(rounds.stopAfter(3, {0.002, 0.003}));
  EXPECT_EQ(rounds.why(), RoundsStop::Settled);
}

// Real scans: every round moves some pose by centimetres, forever.
TEST(OuterRounds, MovesThatStopShrinkingStopTheRounds) {
  const HbaSettings settings = withRounds(100);
  OuterRounds rounds(settings);
  EXPECT_FALSE(rounds.stopAfter(1, {0.1884, 0.9007}));
  EXPECT_FALSE(rounds.stopAfter(2, {0.0831, 0.1380}));
  EXPECT_TRUE(rounds.stopAfter(3, {0.0834, 0.1460}));
  EXPECT_EQ(rounds.why(), RoundsStop::Stalled);
  EXPECT_EQ(rounds.reason(),
            "stopped after 3 rounds: largest move 0.0834 m, 0.1460 deg, no less than the round before "
            "(the noise floor)");
  EXPECT_STREQ(toString(rounds.why()), "moves stopped shrinking");
}

TEST(OuterRounds, TheLimitStopsTheRest) {
  const HbaSettings settings = withRounds(2);
  OuterRounds rounds(settings);
  EXPECT_FALSE(rounds.stopAfter(1, {1.0, 1.0}));
  EXPECT_TRUE(rounds.stopAfter(2, {0.5, 0.5}));
  EXPECT_EQ(rounds.why(), RoundsStop::Limit);
  EXPECT_EQ(rounds.reason(), "reached --iterations 2: largest move 0.5000 m, 0.5000 deg");
  EXPECT_STREQ(toString(rounds.why()), "iteration limit");
  // The default single round: its reason, whatever it moved.
  const HbaSettings one = withRounds(1);
  OuterRounds single(one);
  EXPECT_TRUE(single.stopAfter(1, {0.2, 0.9}));
  EXPECT_EQ(single.why(), RoundsStop::Limit);
}

}  // namespace
}  // namespace hba::pipeline
