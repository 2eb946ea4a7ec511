// The plan of a run (plan.hpp): worked out once from the settings and a few
// scans, and what the run then does.
#include "hba/pipeline/plan.hpp"

#include <gtest/gtest.h>

#include "hba/core/error.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "simulated_sequence.hpp"

namespace hba::pipeline {
namespace {

// 40 flat scans of 5000 points, 0.5 m apart: none is merged by the scan voxel.
io::MemoryScanSource flatScans() {
  std::vector<PointCloud> scans(40);
  for (PointCloud& scan : scans) {
    for (int k = 0; k < 5000; ++k)
      scan.add(Vec3f(0.5f * static_cast<float>(k % 100), 0.5f * static_cast<float>(k / 100), 0.0f));
  }
  return io::MemoryScanSource(std::move(scans));
}

TEST(Plan, AnAutomaticWindowComesFromTheScansRead) {
  const Plan plan = planRun(flatScans(), HbaSettings());  // the default window: automatic
  EXPECT_NEAR(plan.windows.points_per_scan, 5000.0, 1.0);
  EXPECT_EQ(plan.windows.window, 30);  // 150 000 points a window at least
  EXPECT_EQ(plan.windows.stride, 15);
  EXPECT_TRUE(plan.windows.automatic);
  // The settings every stage runs with carry it, and the layers and threads.
  EXPECT_EQ(plan.settings.window, 30);
  EXPECT_EQ(plan.settings.stride, 15);
  EXPECT_EQ(plan.layers, pyramid::layerCount(40, plan.settings));
  EXPECT_GE(plan.settings.threads, 1);
  // The memory estimate is of that run: its windows and layers.
  EXPECT_EQ(plan.memory.layers, plan.layers);
  EXPECT_NEAR(plan.density.sampled_points, 5000.0, 1.0);
}

TEST(Plan, AWindowGivenIsKept) {
  HbaSettings given;
  given.window = 10;
  given.threads = 3;
  const Plan plan = planRun(flatScans(), given);
  EXPECT_EQ(plan.windows.window, 10);
  EXPECT_FALSE(plan.windows.automatic);
  EXPECT_EQ(plan.windows.points_per_scan, 0.0);
  EXPECT_EQ(plan.settings.threads, 3);
}

TEST(Plan, BadSettingsAndNoScansAreRefused) {
  HbaSettings threads;
  threads.threads = -1;
  EXPECT_THROW(planRun(flatScans(), threads), Error);
  HbaSettings stride;
  stride.window = 10;
  stride.stride = 10;
  EXPECT_THROW(planRun(flatScans(), stride), Error);
  EXPECT_THROW(planRun(io::MemoryScanSource({}), HbaSettings()), Error);
}

// A run by a plan made before is the run of those settings, pose for pose,
// and reports the plan; a plan of other scans is refused.
TEST(Plan, TheRunByAPlanIsTheRunOfItsSettings) {
  const test::Sequence drive = test::simulateSequence(test::smallDriveConfig(40));
  const io::MemoryScanSource scans(drive.scans);
  HbaSettings settings;
  settings.threads = 2;
  const Plan plan = planRun(scans, settings);
  const HbaResult planned = runHierarchicalBa(scans, drive.initial, plan);
  const HbaResult direct = runHierarchicalBa(scans, drive.initial, settings);
  ASSERT_EQ(planned.poses.size(), direct.poses.size());
  for (std::size_t i = 0; i < planned.poses.size(); ++i) {
    EXPECT_EQ(planned.poses[i].t, direct.poses[i].t) << i;
    EXPECT_EQ(planned.poses[i].q.coeffs(), direct.poses[i].q.coeffs()) << i;
  }
  EXPECT_EQ(planned.report.windows.window, plan.windows.window);
  EXPECT_EQ(planned.report.layers, plan.layers);
  EXPECT_EQ(planned.report.threads, 2);

  const io::MemoryScanSource fewer(std::vector<PointCloud>(drive.scans.begin(), drive.scans.begin() + 30));
  EXPECT_THROW(
      runHierarchicalBa(fewer, std::vector<Pose>(drive.initial.begin(), drive.initial.begin() + 30), plan),
      Error);
}

}  // namespace
}  // namespace hba::pipeline
