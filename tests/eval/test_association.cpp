// Pairing poses by index and by timestamp.
#include <gtest/gtest.h>

#include "hba/core/error.hpp"
#include "hba/eval/association.hpp"

namespace hba::eval {
namespace {

TEST(Association, ByIndexNeedsEqualCounts) {
  const Association a = associateByIndex(3, 3);
  EXPECT_EQ(a.reference, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(a.estimate, a.reference);
  EXPECT_THROW(associateByIndex(3, 4), Error);
}

TEST(Association, ByTimeTakesTheNearestStampWithinTolerance) {
  const std::vector<double> reference{0.0, 1.0, 2.0, 3.0, 4.0};
  // 0.004 -> 0, 1.02 too far, 2.995 -> 3, 3.001 also nearest to 3 and closer.
  const std::vector<double> estimate{0.004, 1.02, 2.995, 3.001};
  const Association a = associateByTime(reference, estimate, 0.01);
  EXPECT_EQ(a.mode, AssociationMode::Time);
  EXPECT_EQ(a.estimate, (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(a.reference, (std::vector<std::size_t>{0, 3}));
}

TEST(Association, ByTimeHandlesUnsortedReference) {
  const std::vector<double> reference{2.0, 0.0, 1.0};
  const Association a = associateByTime(reference, {0.0, 1.0, 2.0}, 0.001);
  EXPECT_EQ(a.reference, (std::vector<std::size_t>{1, 2, 0}));
  EXPECT_THROW(associateByTime(reference, {10.0}, 0.1), Error);
}

// Nothing within the tolerance: the message gives both sides' stamps, so the
// reader sees at once that one holds seconds since 1970 and the other indices.
TEST(Association, NoMatchSaysBothTimeRanges) {
  try {
    associateByTime({1000.0, 1001.0, 1002.0}, {2.0, 0.0, 1.0}, 0.01);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "no timestamps match within 0.01 s: the reference has 3 stamps from 1000.000 to 1002.000 s, "
                 "the estimate 3 stamps from 0.000 to 2.000 s");
  }
  EXPECT_EQ(pairByTime({1000.0}, {0.0}, 0.01).size(), 0u);
}

TEST(Association, AutoUsesIndexWhenEitherSideHasNoStamps) {
  Trajectory stamped, plain;
  for (int i = 0; i < 4; ++i) {
    stamped.poses.emplace_back();
    stamped.stamps.push_back(100.0 + i);
    plain.poses.emplace_back();
  }
  EXPECT_EQ(associate(stamped, plain, AssociationMode::Auto, 0.01).mode, AssociationMode::Index);
  EXPECT_EQ(associate(stamped, stamped, AssociationMode::Auto, 0.01).mode, AssociationMode::Time);
  EXPECT_THROW(associate(stamped, plain, AssociationMode::Time, 0.01), Error);
}

}  // namespace
}  // namespace hba::eval
