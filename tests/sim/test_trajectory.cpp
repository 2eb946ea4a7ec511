// Trajectories: speed, revisits, sensor height, heading, file input.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/trajectory.hpp"
#include "test_support.hpp"

namespace hba::sim {
namespace {

// Smallest distance between the last frame and any frame of the first half.
double revisitGap(const Trajectory& t) {
  double best = 1e9;
  for (std::size_t k = 0; k < t.size() / 2; ++k) {
    best = std::min(best, (t.poses.back().t - t.poses[k].t).head<2>().norm());
  }
  return best;
}

class SimTrajectoryShapes : public ::testing::TestWithParam<PathShape> {};

TEST_P(SimTrajectoryShapes, DrivesAtSpeedOnTheGroundAndComesBack) {
  const Terrain terrain(4, 0.03);
  TrajectoryConfig config;
  config.shape = GetParam();
  config.frames = 300;
  config.speed = 5.0;
  const Trajectory t = makeTrajectory(config, terrain);
  ASSERT_EQ(t.size(), 300u);
  ASSERT_EQ(t.stamps.size(), 300u);
  EXPECT_DOUBLE_EQ(t.stamps[10], 1.0);
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const Vec3 step = t.poses[k + 1].t - t.poses[k].t;
    EXPECT_NEAR(step.head<2>().norm(), 0.5, 0.02) << "frame " << k;
    // Heading along the tangent.
    EXPECT_GT(t.poses[k].R().col(0).head<2>().normalized().dot(step.head<2>().normalized()), 0.99);
    const Vec3& p = t.poses[k].t;
    EXPECT_NEAR(p.z() - terrain.height(p.x(), p.y()), 1.8, 1e-9);
  }
  EXPECT_LT(revisitGap(t), 1.0) << hba::toString(GetParam()) << " must revisit its start";
}

INSTANTIATE_TEST_SUITE_P(AllShapes, SimTrajectoryShapes,
                         ::testing::Values(PathShape::Block, PathShape::Figure8, PathShape::Street));

TEST(SimTrajectory, PitchFollowsTheSlope) {
  const Terrain terrain(4, 0.05);
  TrajectoryConfig config;
  config.frames = 200;
  const Trajectory t = makeTrajectory(config, terrain);
  double steepest = 0.0;
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    // The forward axis climbs as the road does (the chord's grade; corners
    // turn the chord but not its grade).
    const Vec3 step = t.poses[k + 1].t - t.poses[k].t;
    const double grade = step.z() / step.head<2>().norm();
    const Vec3 forward = t.poses[k].R().col(0);
    EXPECT_NEAR(forward.z() / forward.head<2>().norm(), grade, 2e-3) << "frame " << k;
    steepest = std::max(steepest, std::abs(grade));
    // No roll beyond the lateral slope.
    EXPECT_LT(std::abs(t.poses[k].R().col(1).z()), 0.05);
  }
  EXPECT_GT(steepest, 0.01) << "the test drives on a slope";
}

TEST(SimTrajectory, KittiCameraPosesBecomeZUpLidarPoses) {
  // A camera driving forward (its +z) and turning right (about its -y... i.e.
  // yaw to the right seen from above).
  hba::test::TempDir dir;
  Trajectory camera;
  for (int k = 0; k < 50; ++k) {
    const double yaw_right = 0.01 * k;  // rotation about camera +y turns z towards x (right)
    const Mat3 R = Eigen::AngleAxisd(yaw_right, Vec3::UnitY()).toRotationMatrix();
    camera.poses.emplace_back(R, Vec3(0.2 * k, -0.1 * k, 1.0 * k));  // forward, right, up
  }
  io::writePoses(dir / "kitti.txt", camera, io::PoseFormat::Kitti);
  const PlanarPath path = planarPathFromFile(dir / "kitti.txt", 40);
  ASSERT_EQ(path.positions.size(), 40u);
  // Forward 1 m becomes +x, right 0.2 m becomes -y.
  EXPECT_NEAR(path.positions[10].x(), 10.0, 1e-9);
  EXPECT_NEAR(path.positions[10].y(), -2.0, 1e-9);
  // Turning right is a negative yaw in a z-up frame.
  EXPECT_NEAR(path.headings[0], 0.0, 1e-9);
  EXPECT_NEAR(path.headings[10], -0.1, 1e-9);
}

TEST(SimTrajectory, FollowsTheSharedKittiDrive) {
  const auto file = hba::test::sharedDataDir() / "trajectories" / "kitti00_gt.txt";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no shared data";
  const Terrain terrain(1, 0.03);
  TrajectoryConfig config;
  config.file = file;
  config.frames = 100;
  const Trajectory t = makeTrajectory(config, terrain);
  ASSERT_EQ(t.size(), 100u);
  // KITTI 00 starts by driving straight ahead: along +x of the LiDAR frame.
  EXPECT_GT(t.poses[99].t.x() - t.poses[0].t.x(), 30.0);
  EXPECT_LT(std::abs(t.poses[99].t.y() - t.poses[0].t.y()), 10.0);
}

TEST(SimTrajectory, RejectsBadSettings) {
  const Terrain terrain(1, 0.0);
  TrajectoryConfig config;
  config.frames = 0;
  EXPECT_THROW(makeTrajectory(config, terrain), Error);
  config.frames = 10;
  config.speed = -1.0;
  EXPECT_THROW(makeTrajectory(config, terrain), Error);
  config.speed = 5.0;
  config.file = "/nonexistent/trajectory.txt";
  EXPECT_THROW(makeTrajectory(config, terrain), Error);
  EXPECT_EQ(findEnum<PathShape>("figure8"), PathShape::Figure8);
  EXPECT_FALSE(findEnum<PathShape>("circle").has_value());
}

}  // namespace
}  // namespace hba::sim
