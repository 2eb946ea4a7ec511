// The convention check judges only when the scans can tell the conventions
// apart (issue 57 item 20: 20 000 one-point clouds were called "already
// moved into the world frame").
#include <gtest/gtest.h>

#include <vector>

#include "hba/io/scan_source.hpp"
#include "pipeline/convention_check.hpp"
#include "simulated_sequence.hpp"

namespace hba::pipeline {
namespace {

std::vector<Pose> straightPath(std::size_t frames, double step) {
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < frames; ++i) {
    poses.emplace_back(Quat::Identity(), Vec3(step * static_cast<double>(i), 0.0, 0.0));
  }
  return poses;
}

TEST(ConventionCheck, OnePointCloudsCannotTell) {
  // One point 5 m ahead of the sensor: merged without poses, every scan
  // falls in one voxel, which says nothing about the scans' frame.
  std::vector<PointCloud> clouds(400);
  for (PointCloud& cloud : clouds) cloud.points.emplace_back(5.0f, 0.0f, 0.0f);
  const ConventionCheck check =
      checkConventions(io::MemoryScanSource(std::move(clouds)), straightPath(400, 0.5));
  EXPECT_EQ(check.verdict, ConventionVerdict::AsGiven) << check.message;
  EXPECT_TRUE(check.message.empty()) << check.message;
  EXPECT_NE(check.cannot_tell.find("too few points to tell"), std::string::npos) << check.cannot_tell;
}

TEST(ConventionCheck, ScansOfAPlaceStillTellScansSavedInTheWorld) {
  // The same threshold keeps real scans judged: a simulated drive whose scans
  // were saved moved by their poses is caught.
  const test::Sequence sequence = test::simulateSequence(test::smallDriveConfig(40));
  std::vector<PointCloud> moved;
  for (std::size_t i = 0; i < sequence.scans.size(); ++i) {
    PointCloud cloud = sequence.scans[i];
    const Pose& pose = sequence.truth.poses[i];
    for (Vec3f& p : cloud.points) p = (pose.R() * p.cast<double>() + pose.t).cast<float>();
    moved.push_back(std::move(cloud));
  }
  const ConventionCheck check =
      checkConventions(io::MemoryScanSource(std::move(moved)), sequence.truth.poses);
  EXPECT_TRUE(check.cannot_tell.empty()) << check.cannot_tell;
  EXPECT_EQ(check.verdict, ConventionVerdict::ScansInWorld) << check.message;
}

}  // namespace
}  // namespace hba::pipeline
