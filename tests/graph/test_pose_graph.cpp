#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/graph/pose_graph.hpp"

namespace hba::graph {
namespace {

using test::maxPoseError;
using test::randomVec6;

// A closed loop of `n` poses on a tilted circle, heading along the path.
std::vector<Pose> loopTrajectory(int n, double radius) {
  std::vector<Pose> poses;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    const Vec3 position(radius * std::cos(angle), radius * std::sin(angle), 0.5 * std::sin(3.0 * angle));
    const Mat3 heading = so3Exp(Vec3(0.05 * std::cos(angle), 0.0, angle + M_PI / 2));
    poses.emplace_back(heading, position);
  }
  return poses;
}

RelativePoseFactor exactFactor(const std::vector<Pose>& truth, std::size_t from, std::size_t to,
                               const Mat6& information = Mat6::Identity()) {
  RelativePoseFactor f;
  f.from = from;
  f.to = to;
  f.measurement = relative(truth[from], truth[to]);
  f.information = information;
  return f;
}

// Odometry (i, i+1), short skips (i, i+3) and a loop closure (n-1, 0).
std::vector<RelativePoseFactor> loopFactors(const std::vector<Pose>& truth) {
  std::vector<RelativePoseFactor> factors;
  const std::size_t n = truth.size();
  for (std::size_t i = 0; i + 1 < n; ++i) factors.push_back(exactFactor(truth, i, i + 1));
  for (std::size_t i = 0; i + 3 < n; ++i) factors.push_back(exactFactor(truth, i, i + 3));
  factors.push_back(exactFactor(truth, n - 1, 0));
  return factors;
}

double meanPositionError(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i].t - b[i].t).norm();
  return sum / static_cast<double>(a.size());
}

bool samePose(const Pose& a, const Pose& b) { return a.t == b.t && a.q.coeffs() == b.q.coeffs(); }

TEST(PoseGraph, RecoversTruthFromPerturbedPosesWithConsistentMeasurements) {
  const std::vector<Pose> truth = loopTrajectory(40, 20.0);
  std::mt19937 rng(11);
  std::vector<Pose> initial = truth;
  for (std::size_t i = 1; i < initial.size(); ++i) {
    initial[i] = initial[i] * se3Exp(randomVec6(rng, 1.0, 0.2));
  }
  const std::vector<RelativePoseFactor> factors = loopFactors(truth);
  PoseGraphSettings settings;
  settings.function_tolerance = 1e-16;
  const PoseGraphResult result = optimizePoseGraph(initial, factors, settings);
  EXPECT_GT(result.initial_cost, 1.0);
  EXPECT_LT(result.final_cost, 1e-12);
  EXPECT_LT(maxPoseError(result.poses, truth), 1e-6);
}

// loopFactors(truth) with noise of known covariance, and the poses dead
// reckoning from their odometry factors reaches (drifting; the loop closes it).
struct NoisyLoop {
  std::vector<RelativePoseFactor> factors;
  std::vector<Pose> initial;
};

NoisyLoop noisyLoop(const std::vector<Pose>& truth, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Vec6 sigma;
  sigma << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005;
  const Mat6 information = sigma.cwiseInverse().cwiseAbs2().asDiagonal();

  NoisyLoop loop{loopFactors(truth), {truth[0]}};
  for (RelativePoseFactor& f : loop.factors) {
    Vec6 noise;
    for (int k = 0; k < 6; ++k) noise[k] = sigma[k] * normal(rng);
    f.measurement = f.measurement * se3Exp(noise);
    f.information = information;
  }
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    loop.initial.push_back(loop.initial.back() * loop.factors[i].measurement);
  }
  return loop;
}

TEST(PoseGraph, ReducesDriftWithNoisyMeasurementsOfKnownCovariance) {
  const std::vector<Pose> truth = loopTrajectory(60, 25.0);
  const auto [factors, initial] = noisyLoop(truth, 12);
  const PoseGraphResult result = optimizePoseGraph(initial, factors);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(result.final_cost, result.initial_cost);
  const double before = meanPositionError(initial, truth);
  const double after = meanPositionError(result.poses, truth);
  EXPECT_LT(after, 0.5 * before) << "before " << before << " after " << after;
  // About one chi-square degree of freedom per residual dimension.
  EXPECT_LT(result.final_cost, 6.0 * static_cast<double>(factors.size()));
}

TEST(PoseGraph, EndsAfterAStepThatGainsLessThanItsShareOfTheCost) {
  const std::vector<Pose> truth = loopTrajectory(60, 25.0);
  const auto [factors, initial] = noisyLoop(truth, 12);
  // Ceres' solve, whose own tolerances the share is set against.
  PoseGraphSettings ceres_solve;
  ceres_solve.normal_equations = false;
  PoseGraphSettings to_the_end = ceres_solve;
  to_the_end.last_step_gain = 0.0;
  const PoseGraphResult full = optimizePoseGraph(initial, factors, to_the_end);
  EXPECT_TRUE(full.converged);

  // The default share ends where Ceres' tolerances would, or earlier, at
  // poses no different.
  const PoseGraphResult ended = optimizePoseGraph(initial, factors, ceres_solve);
  EXPECT_TRUE(ended.converged);
  EXPECT_LE(ended.iterations, full.iterations);
  EXPECT_LT(maxPoseError(ended.poses, full.poses), 1e-6);
  EXPECT_NEAR(ended.final_cost, full.final_cost, 1e-9 * full.final_cost);

  // A larger share ends earlier, with the step that gained too little
  // taken: lower than Ceres' function tolerance ends, which drops it.
  PoseGraphSettings share = ceres_solve;
  share.last_step_gain = 1e-3;
  const PoseGraphResult early = optimizePoseGraph(initial, factors, share);
  PoseGraphSettings tolerance = to_the_end;
  tolerance.function_tolerance = 1e-3;
  const PoseGraphResult dropped = optimizePoseGraph(initial, factors, tolerance);
  EXPECT_TRUE(early.converged);
  EXPECT_LT(early.iterations, full.iterations);
  EXPECT_LT(early.final_cost, dropped.final_cost);
  EXPECT_LT(maxPoseError(early.poses, full.poses), maxPoseError(dropped.poses, full.poses));
}

TEST(PoseGraph, HoldsTheGaugeAndLeavesUntouchedNodesAlone) {
  const std::vector<Pose> truth = loopTrajectory(12, 10.0);
  std::mt19937 rng(13);
  std::vector<Pose> initial = truth;
  for (Pose& p : initial) p = p * se3Exp(randomVec6(rng, 0.5, 0.1));
  std::vector<RelativePoseFactor> factors = loopFactors(truth);
  // Node 12 has no factor; nodes 13 and 14 form a second component.
  initial.push_back(Pose(so3Exp(Vec3(0.3, 0.2, 0.1)), Vec3(100, 200, 300)));
  initial.push_back(Pose(so3Exp(Vec3(0.0, 0.0, 1.0)), Vec3(50, 0, 0)));
  initial.push_back(Pose(so3Exp(Vec3(0.0, 0.0, 1.0)), Vec3(55, 0, 0)));
  RelativePoseFactor second;
  second.from = 13;
  second.to = 14;
  second.measurement = Pose(Quat::Identity(), Vec3(1.0, 0.0, 0.0));
  factors.push_back(second);

  const PoseGraphResult result = optimizePoseGraph(initial, factors);
  EXPECT_TRUE(samePose(result.poses[0], initial[0]));
  EXPECT_TRUE(samePose(result.poses[12], initial[12]));
  EXPECT_TRUE(samePose(result.poses[13], initial[13]));
  EXPECT_LT((relative(result.poses[13], result.poses[14]).t - Vec3(1, 0, 0)).norm(), 1e-6);
  // The loop is rebuilt around the fixed (perturbed) first pose.
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose expected = initial[0] * relative(truth[0], truth[i]);
    EXPECT_LT((result.poses[i].t - expected.t).norm(), 1e-6);
  }
}

// Identity rotations held stiff, so the rotations cannot trade against the
// translations (through lever arms), the translation residual is linear and
// the optimum has a closed form.
RelativePoseFactor translationFactor(std::size_t from, std::size_t to, const Vec3& offset, double weight) {
  RelativePoseFactor f;
  f.from = from;
  f.to = to;
  f.measurement = Pose(Quat::Identity(), offset);
  f.information.setZero();
  f.information.diagonal() << weight, weight, weight, 1e8, 1e8, 1e8;
  return f;
}

TEST(PoseGraph, ConflictingFactorsMeetAtTheInformationWeightedMean) {
  const std::vector<Pose> initial(2);
  const std::vector<RelativePoseFactor> factors = {translationFactor(0, 1, Vec3(1, 0, 0), 100.0),  // strong
                                                   translationFactor(0, 1, Vec3(2, 0, 0), 1.0)};   // weak
  const PoseGraphResult result = optimizePoseGraph(initial, factors);
  EXPECT_NEAR(result.poses[1].t.x(), 102.0 / 101.0, 1e-7);
  EXPECT_NEAR(result.poses[1].t.y(), 0.0, 1e-12);
}

TEST(PoseGraph, LoopInconsistencyIsSharedInProportionToCompliance) {
  // Square 0-1-2-3 with a closure 3->0 that is off by `gap` along x. Each
  // factor absorbs a share of the gap proportional to 1 / weight.
  const double gap = 0.3;
  const Vec3 corners[4] = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(0, 4, 0)};
  for (const double closure_weight : {1e-2, 1.0, 1e4}) {
    const double chain_weight = 1.0;
    std::vector<Pose> initial;
    for (const Vec3& c : corners) initial.emplace_back(Quat::Identity(), c);
    std::vector<RelativePoseFactor> factors;
    for (std::size_t i = 0; i < 3; ++i) {
      factors.push_back(translationFactor(i, i + 1, corners[i + 1] - corners[i], chain_weight));
    }
    factors.push_back(translationFactor(3, 0, corners[0] - corners[3] + Vec3(gap, 0, 0), closure_weight));
    const PoseGraphResult result = optimizePoseGraph(initial, factors);

    const double compliance = 3.0 / chain_weight + 1.0 / closure_weight;
    const double chain_share = gap * (1.0 / chain_weight) / compliance;
    // The closure wants node 3 at x = -gap: every chain edge gives chain_share.
    EXPECT_NEAR(result.poses[1].t.x(), 4.0 - chain_share, 1e-6) << closure_weight;
    EXPECT_NEAR(result.poses[3].t.x(), -3.0 * chain_share, 1e-6) << closure_weight;
  }
}

TEST(PoseGraph, RobustLossLimitsTheInfluenceOfAnOutlier) {
  std::vector<Pose> initial;
  for (int i = 0; i < 6; ++i) initial.emplace_back(Quat::Identity(), Vec3(i, 0, 0));
  std::vector<RelativePoseFactor> factors;
  for (std::size_t i = 0; i + 1 < 6; ++i) {
    factors.push_back(translationFactor(i, i + 1, Vec3(1, 0, 0), 100.0));
  }
  factors.push_back(translationFactor(0, 5, Vec3(8, 0, 0), 100.0));  // 3 m wrong

  const PoseGraphResult plain = optimizePoseGraph(initial, factors);
  PoseGraphSettings robust_settings;
  robust_settings.robust_loss = RobustLoss::Cauchy;
  robust_settings.robust_loss_scale = 1.0;
  const PoseGraphResult robust = optimizePoseGraph(initial, factors, robust_settings);
  const double plain_shift = std::abs(plain.poses[5].t.x() - 5.0);
  const double robust_shift = std::abs(robust.poses[5].t.x() - 5.0);
  EXPECT_GT(plain_shift, 1.0);
  EXPECT_LT(robust_shift, 0.1 * plain_shift);
}

TEST(PoseGraph, ReportsTheCostItMinimizes) {
  const std::vector<Pose> truth = loopTrajectory(10, 5.0);
  std::mt19937 rng(14);
  std::vector<Pose> initial = truth;
  for (Pose& p : initial) p = p * se3Exp(randomVec6(rng, 0.3, 0.05));
  std::vector<RelativePoseFactor> factors = loopFactors(truth);
  factors.back().measurement = factors.back().measurement * se3Exp(randomVec6(rng, 0.5, 0.1));
  const PoseGraphResult result = optimizePoseGraph(initial, factors);
  EXPECT_NEAR(result.initial_cost, poseGraphCost(initial, factors), 1e-9 * result.initial_cost);
  EXPECT_NEAR(result.final_cost, poseGraphCost(result.poses, factors), 1e-9);
  EXPECT_GT(result.iterations, 0);
}

TEST(PoseGraph, IsDeterministic) {
  const std::vector<Pose> truth = loopTrajectory(50, 20.0);
  std::mt19937 rng(15);
  std::vector<Pose> initial = truth;
  for (Pose& p : initial) p = p * se3Exp(randomVec6(rng, 0.5, 0.05));
  std::vector<RelativePoseFactor> factors = loopFactors(truth);
  for (RelativePoseFactor& f : factors) {
    f.measurement = f.measurement * se3Exp(randomVec6(rng, 0.02, 0.002));
  }
  PoseGraphSettings settings;
  settings.threads = 2;
  const PoseGraphResult first = optimizePoseGraph(initial, factors, settings);
  const PoseGraphResult second = optimizePoseGraph(initial, factors, settings);
  settings.threads = 1;
  const PoseGraphResult single = optimizePoseGraph(initial, factors, settings);
  for (std::size_t i = 0; i < initial.size(); ++i) {
    EXPECT_TRUE(samePose(first.poses[i], second.poses[i])) << i;
    EXPECT_TRUE(samePose(first.poses[i], single.poses[i])) << i;
  }
}

TEST(PoseGraph, EmptyGraphReturnsTheInitialPoses) {
  const std::vector<Pose> initial = loopTrajectory(5, 3.0);
  const PoseGraphResult result = optimizePoseGraph(initial, {});
  EXPECT_TRUE(result.converged);
  for (std::size_t i = 0; i < initial.size(); ++i) EXPECT_TRUE(samePose(result.poses[i], initial[i]));
}

TEST(PoseGraph, RejectsBadInput) {
  const std::vector<Pose> initial(3);
  EXPECT_THROW(optimizePoseGraph(initial, {translationFactor(0, 3, Vec3::Zero(), 1.0)}), Error);
  EXPECT_THROW(optimizePoseGraph(initial, {translationFactor(1, 1, Vec3::Zero(), 1.0)}), Error);
  EXPECT_THROW(optimizePoseGraph(initial, {translationFactor(0, 1, Vec3::Zero(), -1.0)}), Error);
  RelativePoseFactor nan_information = translationFactor(0, 1, Vec3::Zero(), 1.0);
  nan_information.information(0, 0) = std::nan("");
  EXPECT_THROW(optimizePoseGraph(initial, {nan_information}), Error);
  std::vector<Pose> bad_poses = initial;
  bad_poses[2].t.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(optimizePoseGraph(bad_poses, {translationFactor(0, 1, Vec3::Zero(), 1.0)}), Error);
  PoseGraphSettings settings;
  settings.threads = -1;
  EXPECT_THROW(optimizePoseGraph(initial, {}, settings), Error);
  for (const double gain : {-0.1, 1.0, std::nan("")}) {
    PoseGraphSettings bad_gain;
    bad_gain.last_step_gain = gain;
    EXPECT_THROW(optimizePoseGraph(initial, {}, bad_gain), Error) << gain;
  }
}

}  // namespace
}  // namespace hba::graph
