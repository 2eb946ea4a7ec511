// The windows' finest voxel: kept for dense scans, coarsened for sparse
// ones until a scan holds half a plane's points in a voxel (at ten-scan
// windows; less in larger ones), never above the root voxel, and left
// alone when switched off.
#include <gtest/gtest.h>

#include <map>

#include "hba/core/error.hpp"
#include "hba/pipeline/final_voxel.hpp"

namespace hba::pipeline {
namespace {

TEST(FinalVoxel, PointsPerVoxelAreAveragedOverThePoints) {
  PointCloud scan;
  for (int i = 0; i < 8; ++i) scan.add(Vec3f(0.1f * static_cast<float>(i), 0.5f, 0.5f));  // one cell
  scan.add(Vec3f(3.2f, 0.5f, 0.5f));                                                      // another
  scan.add(Vec3f(3.7f, 0.5f, 0.5f));
  EXPECT_DOUBLE_EQ(scanPointsPerVoxel(scan, 1.0), (64.0 + 4.0) / 10.0);
  EXPECT_DOUBLE_EQ(scanPointsPerVoxel(scan, 4.0), 10.0);  // all in one 4 m cell
  EXPECT_DOUBLE_EQ(scanPointsPerVoxel(PointCloud(), 1.0), 0.0);
}

// Points per voxel as measured on the project's data (docs/pyramid.md).
std::function<double(double)> measured(std::map<double, double> by_size) {
  return [by_size](double size) { return by_size.at(size); };
}

TEST(FinalVoxel, DenseScansKeepTheSettingSparseOnesGoCoarser) {
  HbaSettings settings;  // final 1 m, root 4 m, 20-point planes
  ASSERT_DOUBLE_EQ(settings.local.final_voxel_size, 1.0);
  settings.window = 10;
  const FinalVoxel dense = chooseFinalVoxel(settings, measured({{1.0, 18.5}}));  // simulated Livox
  EXPECT_DOUBLE_EQ(dense.chosen, 1.0);
  EXPECT_FALSE(dense.coarsened);
  const FinalVoxel nclt = chooseFinalVoxel(settings, measured({{1.0, 8.1}, {2.0, 25.4}}));
  EXPECT_DOUBLE_EQ(nclt.chosen, 2.0);
  EXPECT_TRUE(nclt.coarsened);
  EXPECT_DOUBLE_EQ(nclt.scan_points_at_setting, 8.1);
  EXPECT_DOUBLE_EQ(nclt.scan_points_at_chosen, 25.4);
  const FinalVoxel twin = chooseFinalVoxel(settings, measured({{1.0, 2.2}, {2.0, 5.7}, {4.0, 15.2}}));
  EXPECT_DOUBLE_EQ(twin.chosen, 4.0);
  // Never above the root voxel, however sparse.
  const FinalVoxel empty = chooseFinalVoxel(settings, measured({{1.0, 0.0}, {2.0, 0.0}, {4.0, 0.0}}));
  EXPECT_DOUBLE_EQ(empty.chosen, 4.0);
}

// The wanted points shrink with the window: a window of w scans pools w of
// them into a voxel (10 / w of a ten-scan window's wish).
TEST(FinalVoxel, LargerWindowsPoolMoreScansAndKeepFinerVoxels) {
  HbaSettings settings;
  EXPECT_THROW(scanPointsWanted(settings), Error);  // automatic (0): not worked out yet
  settings.window = 10;
  EXPECT_DOUBLE_EQ(scanPointsWanted(settings), 10.0);
  settings.window = 52;  // nclt's automatic windows
  EXPECT_NEAR(scanPointsWanted(settings), 100.0 / 52.0, 1e-12);
  const FinalVoxel nclt = chooseFinalVoxel(settings, measured({{1.0, 8.1}}));
  EXPECT_DOUBLE_EQ(nclt.chosen, 1.0);
  EXPECT_FALSE(nclt.coarsened);
  settings.window = 34;  // the sparse twin's
  const FinalVoxel twin = chooseFinalVoxel(settings, measured({{1.0, 2.2}, {2.0, 5.7}}));
  EXPECT_DOUBLE_EQ(twin.chosen, 2.0);
  settings.window = 5;  // half the reference: a simulated Livox scan no longer suffices at 1 m
  const FinalVoxel livox = chooseFinalVoxel(settings, measured({{1.0, 18.5}, {2.0, 60.0}}));
  EXPECT_DOUBLE_EQ(livox.chosen, 2.0);
}

TEST(FinalVoxel, OffOrWithoutCoarseToFineNothingChanges) {
  HbaSettings settings;
  const auto never = [](double) -> double {
    ADD_FAILURE() << "measured although nothing depends on it";
    return 0.0;
  };
  settings.adapt_final_voxel = false;
  EXPECT_DOUBLE_EQ(chooseFinalVoxel(settings, never).chosen, 1.0);
  settings.adapt_final_voxel = true;
  settings.local.final_voxel_size = 0.0;  // one voxel for every round
  EXPECT_DOUBLE_EQ(chooseFinalVoxel(settings, never).chosen, 0.0);
}

TEST(FinalVoxel, AppliedToTheWindowsAndTheTopBaBelowTheirRoots) {
  HbaSettings settings;
  settings.global.planes.voxel_size = 2.0;
  FinalVoxel voxel;
  voxel.chosen = 4.0;
  const HbaSettings applied = withFinalVoxel(settings, voxel);
  EXPECT_DOUBLE_EQ(applied.local.final_voxel_size, 4.0);
  EXPECT_DOUBLE_EQ(applied.global.final_voxel_size, 2.0);  // its root
  voxel.chosen = 0.5;                                      // finer than a setting: the setting stays
  EXPECT_DOUBLE_EQ(withFinalVoxel(settings, voxel).local.final_voxel_size, 1.0);
}

}  // namespace
}  // namespace hba::pipeline
