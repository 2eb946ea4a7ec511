// The automatic window (window 0): enough scans for kWindowPoints points,
// never below the paper's ten frames, never beyond kMaxAutomaticWindow.
#include <gtest/gtest.h>

#include "hba/core/error.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/window_size.hpp"

namespace hba::pipeline {
namespace {

HbaSettings automatic() {
  HbaSettings s;
  s.window = 0;
  s.stride = 0;
  return s;
}

TEST(WindowSize, AGivenWindowIsKeptAndAStrideOfZeroIsHalfOfIt) {
  HbaSettings s;
  s.window = 12;
  s.stride = 0;
  const WindowSize size = chooseWindowSize(s, 1000.0);
  EXPECT_EQ(size.window, 12);
  EXPECT_EQ(size.stride, 6);
  EXPECT_FALSE(size.automatic);
  s.stride = 7;
  EXPECT_EQ(chooseWindowSize(s, 1000.0).stride, 7);
  s.window = 2;
  s.stride = 0;
  EXPECT_EQ(chooseWindowSize(s, 1000.0).stride, 1);  // never 0
}

TEST(WindowSize, DenseScansKeepTenFramesSparseOnesGetMore) {
  // A simulated VLP-16 at 0.1 m: 19 600 points a scan, the paper's window.
  EXPECT_EQ(chooseWindowSize(automatic(), 19600.0).window, kMinAutomaticWindow);
  // nclt's keyframes (about 2 900 points after downsampling): 52 frames.
  const WindowSize sparse = chooseWindowSize(automatic(), 2898.0);
  EXPECT_TRUE(sparse.automatic);
  EXPECT_EQ(sparse.window, 52);
  EXPECT_EQ(sparse.stride, 26);
  EXPECT_GE(sparse.window * 2898.0, kWindowPoints);
  EXPECT_LT((sparse.window - 1) * 2898.0, kWindowPoints);
  // Nearly empty scans: bounded, not thousands of frames.
  EXPECT_EQ(chooseWindowSize(automatic(), 10.0).window, kMaxAutomaticWindow);
  EXPECT_EQ(chooseWindowSize(automatic(), 0.0).window, kMaxAutomaticWindow);
}

TEST(WindowSize, AnAutomaticWindowStaysAboveAStrideGiven) {
  HbaSettings s = automatic();
  s.stride = 70;
  const WindowSize size = chooseWindowSize(s, 26000.0);
  EXPECT_EQ(size.window, 71);
  EXPECT_EQ(size.stride, 70);
}

TEST(WindowSize, AStrideNotBelowTheWindowGivenIsRefused) {
  HbaSettings s;
  s.window = 10;
  s.stride = 10;
  EXPECT_THROW(chooseWindowSize(s, 1000.0), ValueError);
}

}  // namespace
}  // namespace hba::pipeline
