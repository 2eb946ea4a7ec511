// Windows are optimized in batches whose clouds are held together.
#include <gtest/gtest.h>

#include "window_batches.hpp"

namespace hba::pyramid {
namespace {

TEST(WindowBatches, ScansTakeFourWindowsPerThreadKeyframesOne) {
  EXPECT_EQ(windowsPerBatch(true, 2), 8u);
  EXPECT_EQ(windowsPerBatch(false, 2), 2u);
  EXPECT_EQ(windowsPerBatch(true, 0), 4u);
  EXPECT_EQ(windowsPerBatch(false, 0), 1u);
}

TEST(WindowBatches, EachBatchHoldsTheFramesOfItsUnevenWindows) {
  const std::vector<Window> plan{{0, 6}, {3, 6}, {7, 7}, {12, 5}};
  const auto batches = batchWindows(plan, 3);
  ASSERT_EQ(batches.size(), 2u);
  EXPECT_EQ(batches[0].first_window, 0u);
  EXPECT_EQ(batches[0].end_window, 3u);
  EXPECT_EQ(batches[0].first_frame, 0u);
  EXPECT_EQ(batches[0].end_frame, 14u);
  EXPECT_EQ(batches[1].first_window, 3u);
  EXPECT_EQ(batches[1].end_window, 4u);
  EXPECT_EQ(batches[1].first_frame, 12u);
  EXPECT_EQ(batches[1].end_frame, 17u);
}

TEST(WindowBatches, ABatchEndsAtItsFurthestWindow) {
  // Window 1 ends before window 0 does: the batch still holds window 0's frames.
  const auto batches = batchWindows({{0, 10}, {2, 3}}, 2);
  ASSERT_EQ(batches.size(), 1u);
  EXPECT_EQ(batches[0].end_frame, 10u);
}

TEST(WindowBatches, EveryWindowIsInExactlyOneBatch) {
  const auto plan = planWindows(103, 10, 5);
  for (std::size_t size : {1u, 4u, 8u, 100u}) {
    const auto batches = batchWindows(plan, size);
    std::size_t next = 0;
    for (const WindowBatch& b : batches) {
      EXPECT_EQ(b.first_window, next);
      EXPECT_LE(b.end_window - b.first_window, size);
      next = b.end_window;
    }
    EXPECT_EQ(next, plan.size());
  }
  EXPECT_TRUE(batchWindows({}, 4).empty());
}

}  // namespace
}  // namespace hba::pyramid
