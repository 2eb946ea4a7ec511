// Poses by time: interpolation, extrapolation at the ends, and keyframe
// corrections spread to the poses between keyframes.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/pose.hpp"

namespace hba {
namespace {

Pose yawAt(double yaw, const Vec3& t) { return Pose(Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())), t); }

double angleBetween(const Pose& a, const Pose& b) { return Eigen::AngleAxisd(a.q.inverse() * b.q).angle(); }

// Constant motion: 2 m/s along x, turning at 0.5 rad/s, sampled every 0.5 s.
Trajectory steady() {
  Trajectory trajectory;
  for (int k = 0; k < 5; ++k) {
    const double t = 10.0 + 0.5 * k;
    trajectory.stamps.push_back(t);
    trajectory.poses.push_back(yawAt(0.5 * (t - 10.0), Vec3(2.0 * (t - 10.0), 0, 0)));
  }
  return trajectory;
}

TEST(PoseAtTime, InterpolatesBetweenAndExtrapolatesAShortWayBeyond) {
  const Trajectory trajectory = steady();
  const auto expected = [](double t) { return yawAt(0.5 * (t - 10.0), Vec3(2.0 * (t - 10.0), 0, 0)); };
  for (const double t : {10.0, 10.2, 11.3, 12.0, 9.8, 12.4}) {
    SCOPED_TRACE(t);
    const Pose pose = poseAtTime(trajectory, t);
    EXPECT_LT((pose.t - expected(t).t).norm(), 1e-12);
    EXPECT_LT(angleBetween(pose, expected(t)), 1e-12);
  }
  // At most one segment (0.5 s) beyond an end, then held.
  EXPECT_LT((poseAtTime(trajectory, 20.0).t - expected(12.5).t).norm(), 1e-12);
  EXPECT_LT((poseAtTime(trajectory, 0.0).t - expected(9.5).t).norm(), 1e-12);
  // Exactly at a stamp: that pose.
  EXPECT_EQ(poseAtTime(trajectory, 11.0).t, trajectory.poses[2].t);
  Trajectory one;
  one.poses = {yawAt(1.0, Vec3(1, 2, 3))};
  one.stamps = {4.0};
  EXPECT_EQ(poseAtTime(one, 7.0).t, Vec3(1, 2, 3));
}

TEST(SpreadCorrections, ScansBetweenKeyframesMoveAsTheKeyframesAroundThem) {
  // Keyframes at 10, 11 and 12 s; scans every 0.25 s from 9.5 to 12.5 s.
  Trajectory dense;
  for (int i = 0; i <= 12; ++i) {
    const double t = 9.5 + 0.25 * i;
    dense.stamps.push_back(t);
    dense.poses.push_back(yawAt(0.3 * t, Vec3(t, 0.1 * t * t, 0)));
  }
  Trajectory before;
  for (const double t : {10.0, 11.0, 12.0}) {
    before.stamps.push_back(t);
    before.poses.push_back(yawAt(0.3 * t, Vec3(t, 0.1 * t * t, 0)));
  }
  // One correction for all: every scan moves by it, whatever its own motion.
  const Pose shift = yawAt(0.02, Vec3(0.3, -0.2, 0.05));
  std::vector<Pose> after;
  for (const Pose& pose : before.poses) after.push_back(shift * pose);
  const Trajectory moved = spreadCorrections(before, after, dense);
  ASSERT_EQ(moved.size(), dense.size());
  EXPECT_EQ(moved.stamps, dense.stamps);
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const Pose expected = shift * dense.poses[i];
    EXPECT_LT((moved.poses[i].t - expected.t).norm(), 1e-12) << i;
    EXPECT_LT(angleBetween(moved.poses[i], expected), 1e-12) << i;
  }
  // Corrections that differ: halfway between keyframes, half of each; held beyond the ends.
  after = before.poses;
  after[1].t += Vec3(0.0, 0.4, 0.0);
  const Trajectory bent = spreadCorrections(before, after, dense);
  const auto offset = [&](double t) {
    for (std::size_t i = 0; i < dense.size(); ++i) {
      if (std::abs(dense.stamps[i] - t) < 1e-9) return (bent.poses[i].t - dense.poses[i].t).y();
    }
    return std::nan("");
  };
  EXPECT_NEAR(offset(11.0), 0.4, 1e-12);
  EXPECT_NEAR(offset(10.5), 0.2, 1e-12);
  EXPECT_NEAR(offset(11.75), 0.1, 1e-12);
  EXPECT_NEAR(offset(9.5), 0.0, 1e-12);
  EXPECT_NEAR(offset(12.5), 0.0, 1e-12);
}

}  // namespace
}  // namespace hba
