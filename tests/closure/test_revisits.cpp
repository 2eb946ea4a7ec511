#include <gtest/gtest.h>

#include "closure_paths.hpp"
#include "hba/closure/revisits.hpp"
#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

TEST(Revisits, AClosedCircleRevisitsItsStartOnlyAtTheEnd) {
  // 400 frames round a 60 m circle (377 m path): only the last frames come
  // back to the first ones.
  const std::vector<Pose> truth = test::circle(400, 60.0);
  const auto found = findRevisits(truth, RevisitSettings{});
  ASSERT_FALSE(found.empty());
  for (const RevisitCandidate& c : found) {
    EXPECT_GT(c.to, 350u);
    EXPECT_LT(c.from, 50u);
    EXPECT_GE(c.path_m, 50.0);
    EXPECT_LE(c.distance_m, 10.0 + c.search_radius_m);
  }
  // One candidate per 10 m of the later visit at most.
  for (std::size_t k = 1; k < found.size(); ++k) {
    EXPECT_GE((truth[found[k].to].t - truth[found[k - 1].to].t).norm(), 9.0);
  }
}

TEST(Revisits, AStraightDriveHasNone) {
  std::vector<Pose> line;
  for (int k = 0; k < 500; ++k) line.emplace_back(Quat::Identity(), Vec3(0.5 * k, 0.0, 0.0));
  EXPECT_TRUE(findRevisits(line, RevisitSettings{}).empty());
}

TEST(Revisits, DriftWidensTheReachAndTheSearch) {
  // The odometry's heading bias opens the circle by metres: beyond the
  // reach alone, within reach + drift x path.
  const std::vector<Pose> truth = test::circle(400, 60.0);
  const std::vector<Pose> odometry = test::drifted(truth, 0.04, 0.0, 1);
  const double gap = (odometry.back().t - odometry.front().t).norm();
  ASSERT_GT(gap, 12.0);
  RevisitSettings no_drift;
  no_drift.drift = 0.0;
  const auto strict = findRevisits(odometry, no_drift);
  const auto found = findRevisits(odometry, RevisitSettings{});
  EXPECT_LT(strict.size(), found.size());
  ASSERT_FALSE(found.empty());
  const RevisitCandidate& last = found.back();
  EXPECT_NEAR(last.search_radius_m, std::min(0.05 * last.path_m, 30.0), 1e-9);
  EXPECT_NEAR(last.search_yaw_deg, std::min(0.05 * last.path_m, 30.0), 1e-9);
}

TEST(Revisits, RejectsSettingsThatAreNotPositive) {
  RevisitSettings bad;
  bad.reach_m = 0.0;
  EXPECT_THROW(findRevisits(test::circle(10, 5.0), bad), Error);
  bad = RevisitSettings{};
  bad.drift = -0.1;
  EXPECT_THROW(findRevisits(test::circle(10, 5.0), bad), Error);
}

}  // namespace
}  // namespace hba::closure

namespace hba::closure {
namespace {

// Session A drives +x from 0 to 150 m; session B drives the same street from
// 60 m on, its frame 8 m and 5 degrees off (an initial alignment's error).
std::vector<Pose> twoSessions(std::size_t& b_start) {
  std::vector<Pose> poses;
  for (int k = 0; k < 300; ++k) poses.emplace_back(Quat::Identity(), Vec3(0.5 * k, 0.0, 0.0));
  b_start = poses.size();
  const Pose offset(Mat3(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Vec3::UnitZ())), Vec3(3.0, 7.0, 0.0));
  for (int k = 0; k < 200; ++k)
    poses.push_back(offset * Pose(Quat::Identity(), Vec3(60.0 + 0.5 * k, 0.0, 0.0)));
  return poses;
}

TEST(Revisits, SessionsMeetWhereverTheyOverlapWithTheWidestSearch) {
  std::size_t b_start = 0;
  const std::vector<Pose> poses = twoSessions(b_start);
  const auto found = findRevisits(poses, RevisitSettings{}, {b_start});
  ASSERT_GE(found.size(), 5u);
  for (const RevisitCandidate& c : found) {
    EXPECT_TRUE(c.cross_session);
    EXPECT_LT(c.from, b_start);
    EXPECT_GE(c.to, b_start);
    EXPECT_EQ(c.search_radius_m, 30.0);
    EXPECT_EQ(c.search_yaw_deg, 30.0);
    EXPECT_LE(c.distance_m, 40.0);
  }
}

}  // namespace
}  // namespace hba::closure
