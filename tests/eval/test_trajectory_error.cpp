// ATE / RPE / alignment on constructed trajectories with hand-computed answers.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/eval/trajectory_error.hpp"

namespace hba::eval {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A helix that turns and climbs, with a varying orientation: no alignment
// degeneracy (positions are not collinear or coplanar).
Trajectory helix(std::size_t n) {
  Trajectory t;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 0.3 * static_cast<double>(i);
    const Vec3 position(5.0 * std::cos(a), 5.0 * std::sin(a), 0.4 * static_cast<double>(i));
    t.poses.emplace_back(Mat3(so3Exp(Vec3(0.05 * std::sin(a), 0.02 * a, a))), position);
  }
  return t;
}

Trajectory transformed(const Trajectory& in, const Pose& offset) {
  Trajectory out = in;
  for (Pose& p : out.poses) p = offset * p;
  return out;
}

EvalOptions withAlignment(Alignment alignment) {
  EvalOptions o;
  o.alignment = alignment;
  return o;
}

TEST(Ate, RigidOffsetVanishesWithSe3Alignment) {
  const Trajectory gt = helix(40);
  const Pose offset(Mat3(so3Exp(Vec3(0.2, -0.4, 1.1))), Vec3(3.0, -7.0, 2.0));
  const TrajectoryEvaluation r =
      evaluateTrajectory(gt, transformed(gt, offset), withAlignment(Alignment::SE3));
  EXPECT_EQ(r.matched, 40u);
  EXPECT_LT(r.ate.translation_m.max, 1e-9);
  EXPECT_LT(r.ate.rotation_deg.max, 1e-6);
  EXPECT_NEAR(r.alignment.scale, 1.0, 1e-12);
  // The alignment found is the inverse of the offset applied.
  EXPECT_LT((r.alignment.R - offset.inverse().R()).norm(), 1e-9);
  EXPECT_LT((r.alignment.t - offset.inverse().t).norm(), 1e-9);
}

TEST(Ate, PureTranslationOffsetWithoutAlignmentIsTheOffset) {
  const Trajectory gt = helix(25);
  const Pose offset(Quat::Identity(), Vec3(1.0, 2.0, 2.0));  // |offset| = 3
  const TrajectoryEvaluation r =
      evaluateTrajectory(gt, transformed(gt, offset), withAlignment(Alignment::None));
  EXPECT_NEAR(r.ate.translation_m.rmse, 3.0, 1e-12);
  EXPECT_NEAR(r.ate.translation_m.mean, 3.0, 1e-12);
  EXPECT_NEAR(r.ate.translation_m.median, 3.0, 1e-12);
  EXPECT_NEAR(r.ate.translation_m.max, 3.0, 1e-12);
  EXPECT_LT(r.ate.rotation_deg.max, 1e-6);
}

TEST(Ate, RotationOffsetWithoutAlignmentGivesItsAngle) {
  // Rotating the world by 90 degrees about z about the origin: every pose's
  // orientation error is 90 degrees; a pose at distance d from the z axis
  // moves by d * sqrt(2).
  Trajectory gt;
  for (int i = 0; i < 5; ++i) gt.poses.emplace_back(Quat::Identity(), Vec3(2.0, 0.0, i));
  const Pose offset(Mat3(so3Exp(Vec3(0, 0, 90 * kDeg))), Vec3::Zero());
  const TrajectoryEvaluation r =
      evaluateTrajectory(gt, transformed(gt, offset), withAlignment(Alignment::None));
  EXPECT_NEAR(r.ate.rotation_deg.rmse, 90.0, 1e-9);
  EXPECT_NEAR(r.ate.translation_m.max, 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(Ate, Sim3RecoversScaleThatSe3CannotExplain) {
  const Trajectory gt = helix(30);
  Trajectory est = gt;
  const Pose offset(Mat3(so3Exp(Vec3(0.0, 0.3, -0.5))), Vec3(1.0, 1.0, -4.0));
  for (Pose& p : est.poses) {
    p.t *= 0.5;  // the estimate is half the true size
    p = offset * p;
  }
  const TrajectoryEvaluation sim3 = evaluateTrajectory(gt, est, withAlignment(Alignment::Sim3));
  EXPECT_NEAR(sim3.alignment.scale, 2.0, 1e-9);
  EXPECT_LT(sim3.ate.translation_m.max, 1e-9);
  EXPECT_LT(sim3.ate.rotation_deg.max, 1e-6);
  EXPECT_LT(sim3.rpe.translation_m.max, 1e-9);  // RPE uses the scaled estimate too

  const TrajectoryEvaluation se3 = evaluateTrajectory(gt, est, withAlignment(Alignment::SE3));
  EXPECT_GT(se3.ate.translation_m.rmse, 1.0);
  EXPECT_GT(se3.rpe.translation_m.mean, 0.1);
}

TEST(Ate, OneBadPoseGivesHandComputedStatistics) {
  // 10 perfect poses but pose 6, which is 1 m off and turned by 30 degrees:
  // translation errors {0 x9, 1}: RMSE sqrt(1/10), mean 0.1, median 0, max 1;
  // rotation errors {0 x9, 30}: RMSE sqrt(900/10), mean 3, max 30.
  Trajectory gt = helix(10);
  Trajectory est = gt;
  est.poses[6].t += Vec3(0.0, 0.6, 0.8);
  est.poses[6].q = est.poses[6].q * Quat(so3Exp(Vec3(30 * kDeg, 0, 0)));
  const TrajectoryEvaluation r = evaluateTrajectory(gt, est, withAlignment(Alignment::None));
  EXPECT_NEAR(r.ate.translation_m.rmse, std::sqrt(0.1), 1e-12);
  EXPECT_NEAR(r.ate.translation_m.mean, 0.1, 1e-12);
  EXPECT_NEAR(r.ate.translation_m.median, 0.0, 1e-12);
  EXPECT_NEAR(r.ate.translation_m.max, 1.0, 1e-12);
  EXPECT_NEAR(r.ate.rotation_deg.rmse, std::sqrt(90.0), 1e-9);
  EXPECT_NEAR(r.ate.rotation_deg.mean, 3.0, 1e-9);
  EXPECT_NEAR(r.ate.rotation_deg.max, 30.0, 1e-9);
  // RPE over 1 frame: pairs (5,6) and (6,7) see the bad pose, 7 pairs do not.
  EXPECT_EQ(r.rpe.translation_m.count, 9u);
  EXPECT_NEAR(r.rpe.rotation_deg.max, 30.0, 1e-9);
  EXPECT_NEAR(r.rpe.rotation_deg.mean, 60.0 / 9.0, 1e-9);
}

// Ground truth walks 1 m a frame along x; the estimate walks 1.1 m a frame.
std::pair<Trajectory, Trajectory> stretchedLine(std::size_t n) {
  Trajectory gt, est;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    gt.poses.emplace_back(Quat::Identity(), Vec3(x, 0, 0));
    est.poses.emplace_back(Quat::Identity(), Vec3(1.1 * x, 0, 0));
  }
  return {gt, est};
}

TEST(Rpe, StretchedStepsOverFramesAndMetres) {
  const auto [gt, est] = stretchedLine(12);
  const std::vector<Pose>& q = gt.poses;
  const std::vector<Pose>& p = est.poses;
  const PoseErrors one = relativeErrors(q, p, rpePairs(q, 1, DeltaUnit::Frames));
  EXPECT_EQ(one.translation_m.count, 11u);
  EXPECT_NEAR(one.translation_m.rmse, 0.1, 1e-12);
  EXPECT_NEAR(one.translation_m.max, 0.1, 1e-12);
  const PoseErrors three = relativeErrors(q, p, rpePairs(q, 3, DeltaUnit::Frames));
  EXPECT_EQ(three.translation_m.count, 9u);
  EXPECT_NEAR(three.translation_m.mean, 0.3, 1e-12);
  // 2.5 m of ground-truth path is first reached 3 frames later.
  const auto metre_pairs = rpePairs(q, 2.5, DeltaUnit::Meters);
  ASSERT_EQ(metre_pairs.size(), 9u);
  EXPECT_EQ(metre_pairs.front(), std::make_pair(std::size_t{0}, std::size_t{3}));
  EXPECT_NEAR(relativeErrors(q, p, metre_pairs).translation_m.median, 0.3, 1e-12);
}

TEST(Rpe, YawDriftGivesItsIncrementAndIgnoresAGlobalOffset) {
  // Ground truth turns about z only; the estimate yaws 2 degrees more every
  // frame. Rotations about one axis commute, so each relative motion over one
  // frame is off by exactly 2 degrees, over 3 frames by 6, whatever rigid
  // offset the whole estimate has.
  Trajectory gt, est;
  for (int i = 0; i < 20; ++i) {
    const double a = 0.3 * i;
    const Vec3 position(5.0 * std::cos(a), 5.0 * std::sin(a), 0.4 * i);
    gt.poses.emplace_back(Mat3(so3Exp(Vec3(0, 0, a))), position);
    est.poses.emplace_back(Mat3(so3Exp(Vec3(0, 0, a + 2.0 * kDeg * i))), position);
  }
  est = transformed(est, Pose(Mat3(so3Exp(Vec3(1, 2, 3))), Vec3(10, 20, 30)));
  const PoseErrors one = relativeErrors(gt.poses, est.poses, rpePairs(gt.poses, 1, DeltaUnit::Frames));
  EXPECT_NEAR(one.rotation_deg.mean, 2.0, 1e-9);
  EXPECT_NEAR(one.rotation_deg.max, 2.0, 1e-9);
  const PoseErrors three = relativeErrors(gt.poses, est.poses, rpePairs(gt.poses, 3, DeltaUnit::Frames));
  EXPECT_NEAR(three.rotation_deg.rmse, 6.0, 1e-9);
}

TEST(Rpe, RejectsBadDeltas) {
  const Trajectory gt = helix(5);
  EXPECT_THROW(rpePairs(gt.poses, 0, DeltaUnit::Frames), Error);
  EXPECT_THROW(rpePairs(gt.poses, 1.5, DeltaUnit::Frames), Error);
  EXPECT_TRUE(rpePairs(gt.poses, 10, DeltaUnit::Frames).empty());
}

TEST(Umeyama, RecoversAGeneralSimilarity) {
  std::vector<Vec3> source, target;
  const Mat3 R = so3Exp(Vec3(-0.7, 0.2, 2.5));
  const Vec3 t(0.5, -3.0, 8.0);
  for (int i = 0; i < 20; ++i) {
    source.emplace_back(std::sin(i), std::cos(3.0 * i), 0.1 * i * i);
    target.push_back(1.7 * (R * source.back()) + t);
  }
  const Similarity s = umeyama(source, target, true);
  EXPECT_NEAR(s.scale, 1.7, 1e-10);
  EXPECT_LT((s.R - R).norm(), 1e-10);
  EXPECT_LT((s.t - t).norm(), 1e-9);
  EXPECT_NEAR(s.R.determinant(), 1.0, 1e-12);
}

TEST(Umeyama, RejectsDegenerateInput) {
  const std::vector<Vec3> two(2, Vec3::Zero());
  EXPECT_THROW(umeyama(two, two, false), Error);
  const std::vector<Vec3> same(5, Vec3(1, 2, 3));
  EXPECT_THROW(umeyama(same, same, true), Error);
}

TEST(ErrorStats, MedianOfEvenCountIsTheMiddleMean) {
  const ErrorStats s = summarize({4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_EQ(summarize({}).count, 0u);
}

// Per-pose errors for plots: the estimate's stamps and each pose's ATE.
TEST(TrajectoryErrorPerPose, TimesAndErrorsOfEveryMatchedPose) {
  Trajectory reference, estimate;
  for (int i = 0; i < 5; ++i) {
    reference.poses.push_back(Pose(Quat::Identity(), Vec3(i, 0, 0)));
    reference.stamps.push_back(10.0 + i);
    estimate.poses.push_back(Pose(Quat::Identity(), Vec3(i, i == 3 ? 0.5 : 0.0, 0)));
    estimate.stamps.push_back(10.0 + i);
  }
  EvalOptions options;
  options.alignment = Alignment::None;
  const TrajectoryEvaluation r = evaluateTrajectory(reference, estimate, options);
  ASSERT_EQ(r.pose_times.size(), 5u);
  EXPECT_EQ(r.pose_times[4], 14.0);
  EXPECT_DOUBLE_EQ(r.ate_translation_m[3], 0.5);
  EXPECT_DOUBLE_EQ(r.ate_translation_m[2], 0.0);
  EXPECT_DOUBLE_EQ(r.ate.translation_m.max, 0.5);
}

// evo's std is numpy's default: divided by n. 1..4: variance 1.25.
TEST(ErrorStats, StdIsThePopulationStdAndMinIsTheSmallest) {
  const ErrorStats s = summarize({4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  // Large equal values: no cancellation (sum_sq/n - mean^2 would not be 0).
  EXPECT_LT(summarize({1e8 + 0.1, 1e8 + 0.1, 1e8 + 0.1}).std, 1e-6);
}

}  // namespace
}  // namespace hba::eval
