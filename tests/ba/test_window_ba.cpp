#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>

#include <tbb/global_control.h>
#include <Eigen/Eigenvalues>

#include "hba/ba/association.hpp"
#include "hba/ba/lm_solver.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/core/error.hpp"
#include "random_planes.hpp"
#include "synthetic_window.hpp"

namespace hba::ba {
namespace {

using test::makeSyntheticWindow;
using test::relativePoseError;
using test::SyntheticWindowSpec;

BaSettings syntheticSettings() {
  BaSettings settings = test::patchBaSettings();
  // Each frame starts 0.2 m and 1 deg off on its own, further from its
  // neighbours than any odometry: the slide check (tested below) would
  // refuse the correction.
  settings.slide_sigmas = 0.0;
  // These tests follow the BA to its optimum, also from the truth; the
  // settle check (test_offset_noise.cpp) would keep such a start.
  settings.significant_gain = 0.0;
  return settings;
}

// A window of 2 cm point noise.
test::SyntheticWindow noisyWindow(std::uint32_t seed) {
  SyntheticWindowSpec spec;
  spec.noise_sigma = 0.02;
  spec.seed = seed;
  return makeSyntheticWindow(spec);
}

TEST(WindowBa, NoiseFreeWindowConvergesToTruth) {
  const auto window = makeSyntheticWindow(SyntheticWindowSpec{});
  const auto before = relativePoseError(window.initial, window.truth);
  ASSERT_GT(before.max_angle_deg, 0.5);  // the start really is wrong

  // The plane BA alone reaches the truth exactly; the motion prior's pull
  // towards the (deliberately wrong) input is tested in test_motion_prior.
  BaSettings settings = syntheticSettings();
  settings.motion_prior.enabled = false;
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, settings);
  const auto after = relativePoseError(result.poses, window.truth);
  std::printf("noise-free: %.3g deg %.3g m -> %.3g deg %.3g m, %d iterations\n", before.max_angle_deg,
              before.max_translation, after.max_angle_deg, after.max_translation, result.iterations);
  EXPECT_LT(after.max_angle_deg, 0.01);
  EXPECT_LT(after.max_translation, 1e-3);
  EXPECT_GE(result.num_planes, 8u);
  EXPECT_LT(result.final_cost, 1e-4 * result.initial_cost);
  // Frame 0 is the gauge: untouched.
  EXPECT_EQ(result.poses[0].t, window.initial[0].t);
  EXPECT_EQ(result.poses[0].q.coeffs(), window.initial[0].q.coeffs());
}

TEST(WindowBa, NoisyWindowConvergesToNoiseLevel) {
  SyntheticWindowSpec spec;
  spec.noise_sigma = 0.02;
  spec.seed = 4;
  const auto window = makeSyntheticWindow(spec);
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, syntheticSettings());
  const auto after = relativePoseError(result.poses, window.truth);
  // The best any estimator can do here: the cost minimum found from the
  // true poses. The perturbed start must reach the same minimum.
  const BaResult oracle = optimizeWindow(window.scanPointers(), window.truth, syntheticSettings());
  const auto floor = relativePoseError(oracle.poses, window.truth);
  const auto gap = relativePoseError(result.poses, oracle.poses);
  std::printf(
      "noise %.3g m: -> %.3g deg %.3g m (minimum from truth: %.3g deg %.3g m), "
      "%d iterations\n",
      spec.noise_sigma, after.max_angle_deg, after.max_translation, floor.max_angle_deg,
      floor.max_translation, result.iterations);
  EXPECT_LT(gap.max_angle_deg, 5e-3);  // far below the error itself
  EXPECT_LT(gap.max_translation, 5e-4);
  // The noise level: ~sigma / sqrt(points per patch and frame) on 6 m patches.
  EXPECT_LT(after.max_angle_deg, 0.1);
  EXPECT_LT(after.max_translation, 0.01);
  // The residual RMS ends at the point noise (the planes are exact).
  std::vector<double> rms = result.plane_rms_final;
  std::sort(rms.begin(), rms.end());
  EXPECT_NEAR(rms[rms.size() / 2], spec.noise_sigma, 0.3 * spec.noise_sigma);
}

// With the slide check on, a result that moves neighbouring frames apart by
// more than three prior sigmas (here the correction of start errors no
// odometry makes) is not trusted: the window keeps its input poses.
TEST(WindowBa, ResultThatPullsNeighboursApartIsNotTrusted) {
  const auto window = noisyWindow(4);
  BaSettings settings = syntheticSettings();
  const BaResult free = optimizeWindow(window.scanPointers(), window.initial, settings);
  ASSERT_TRUE(free.trusted);
  ASSERT_FALSE(stepsBeyondThePrior(window.initial, free.poses, {}, settings.motion_prior, 3.0).empty());
  settings.slide_sigmas = 3.0;
  const BaResult checked = optimizeWindow(window.scanPointers(), window.initial, settings);
  EXPECT_FALSE(checked.trusted);
  for (std::size_t i = 0; i < checked.poses.size(); ++i) {
    EXPECT_EQ(checked.poses[i].t, window.initial[i].t) << "frame " << i;
  }
}

// Coarse to fine, the trust check's planes come with the first round's
// (one placing of the points): they must be the finest association at the
// input poses, as if found on their own.
TEST(WindowBa, TrustCheckUsesTheFinestPlanesAtTheInput) {
  const auto window = noisyWindow(6);
  BaSettings settings = syntheticSettings();
  settings.final_voxel_size = 2.0;  // rounds at 8, 4 and 2 m
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, settings);
  ASSERT_GT(result.rounds, 1);
  PlaneSettings finest = settings.planes;
  finest.voxel_size = settings.final_voxel_size;
  const PlaneProblem fixed =
      associate(window.scanPointers(), window.initial, finest, settings.reject_ratio).problem;
  ASSERT_GT(fixed.numPlanes(), 0u);
  EXPECT_EQ(result.fixed_map_cost_initial, fixed.cost(window.initial));
  EXPECT_EQ(result.fixed_map_cost_final, fixed.cost(result.poses));
}

// The outlier filter's per-plane costs are kept for the planes it keeps, in
// their order: a solver started at the association's poses takes them as
// its first cost, so they must be problem.planeCosts() there to the bit.
TEST(Association, KeepsEachKeptPlanesCostAtItsPoses) {
  const auto window = noisyWindow(7);
  PlaneSettings planes = syntheticSettings().planes;
  planes.voxel_size = 2.0;  // many planes, so that the filter drops some
  const Association association = associate(window.scanPointers(), window.initial, planes, 0.2);
  const PlaneProblem& problem = association.problem;
  ASSERT_GT(problem.numPlanes(), 10u);
  EXPECT_EQ(association.plane_costs, problem.planeCosts(window.initial));
  EXPECT_EQ(association.cost(), problem.cost(window.initial));
  // Elsewhere they are not the costs.
  EXPECT_NE(association.cost(), problem.cost(window.truth));
}

// A noisy window's planes at its input poses, and its motion prior: what
// its first round's solver is given.
struct WindowProblem {
  test::SyntheticWindow window = noisyWindow(8);
  BaSettings settings = syntheticSettings();
  Association association =
      associate(window.scanPointers(), window.initial, settings.planes, settings.reject_ratio);
  MotionPrior prior = neighbourPrior(window.initial, {}, settings.motion_prior);
};

// Given the cost at the start, the solver takes the same steps as when it
// evaluates that cost itself.
TEST(LevenbergMarquardt, AKnownStartCostGivesTheSameSteps) {
  const WindowProblem w;
  const auto& [window, settings, association, prior] = w;
  std::vector<Pose> evaluated = window.initial;
  std::vector<Pose> given = window.initial;
  const LmSettings lm{settings.max_iterations, settings.relative_cost_tolerance};
  const LmSummary a = solveLevenbergMarquardt(association.problem, evaluated, lm, prior);
  const LmSummary b = solveLevenbergMarquardt(association.problem, given, lm, prior, association.cost());
  ASSERT_GT(a.accepted_steps, 0);
  EXPECT_EQ(a.initial_cost, b.initial_cost);
  EXPECT_EQ(a.final_cost, b.final_cost);
  EXPECT_EQ(a.iterations, b.iterations);
  for (std::size_t i = 0; i < given.size(); ++i) {
    EXPECT_EQ(evaluated[i].t, given[i].t);
    EXPECT_EQ(evaluated[i].R(), given[i].R());
  }
}

// A solve that settles (its last step gained at most the tolerance's share
// of the cost) hands out the linearization that step started from, bit for
// bit the one made there afresh; asking for it changes no step.
TEST(LevenbergMarquardt, HandsOutTheLinearizationWhereItSettled) {
  const WindowProblem w;
  const auto& [window, settings, association, prior] = w;
  const LmSettings lm{50, 1e-4};
  std::vector<Pose> poses = window.initial;
  Linearization settled;
  const LmSummary s = solveLevenbergMarquardt(association.problem, poses, lm, prior, std::nullopt, &settled);
  ASSERT_GT(s.accepted_steps, 1);
  ASSERT_LT(s.iterations, lm.max_iterations);
  ASSERT_GT(settled.gradient.size(), 0);

  std::vector<Pose> plain = window.initial;
  const LmSummary p = solveLevenbergMarquardt(association.problem, plain, lm, prior);
  EXPECT_EQ(p.iterations, s.iterations);
  for (std::size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(plain[i].t, poses[i].t);

  // Where the last step started: the same solve, one iteration short.
  std::vector<Pose> before = window.initial;
  solveLevenbergMarquardt(association.problem, before,
                          LmSettings{s.iterations - 1, lm.relative_cost_tolerance}, prior);
  EXPECT_NE(before[1].t, poses[1].t);
  Linearization expected = association.problem.linearize(before);
  prior.addTo(expected, before);
  EXPECT_EQ(settled.cost, expected.cost);
  EXPECT_EQ(settled.gradient, expected.gradient);
  EXPECT_EQ(settled.hessian, expected.hessian);

  // Cut off by the iteration cap after a larger step: nothing to hand out.
  std::vector<Pose> capped = window.initial;
  Linearization none;
  solveLevenbergMarquardt(association.problem, capped, LmSettings{1, lm.relative_cost_tolerance}, prior,
                          std::nullopt, &none);
  EXPECT_EQ(none.gradient.size(), 0);
}

TEST(WindowBa, IdenticalResultsWithOneAndTwoThreads) {
  SyntheticWindowSpec spec;
  spec.noise_sigma = 0.01;
  const auto window = makeSyntheticWindow(spec);
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return optimizeWindow(window.scanPointers(), window.initial, syntheticSettings());
  };
  const BaResult one = run(1);
  const BaResult two = run(2);
  ASSERT_EQ(one.poses.size(), two.poses.size());
  for (std::size_t i = 0; i < one.poses.size(); ++i) {
    EXPECT_EQ(one.poses[i].t, two.poses[i].t);
    EXPECT_EQ(one.poses[i].q.coeffs(), two.poses[i].q.coeffs());
  }
  EXPECT_EQ(one.final_cost, two.final_cost);
  EXPECT_EQ(one.hessian, two.hessian);
  EXPECT_EQ(one.plane_point_indices, two.plane_point_indices);
}

TEST(WindowBa, HessianAtSolutionHasOnlyTheGaugeFreedom) {
  SyntheticWindowSpec spec;
  spec.noise_sigma = 0.01;
  const auto window = makeSyntheticWindow(spec);
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, syntheticSettings());
  const Eigen::Index n = result.hessian.rows();
  ASSERT_EQ(n, 6 * spec.frames);
  // Moving every frame by the same translation changes nothing: H v = 0.
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    for (int f = 0; f < spec.frames; ++f) v(6 * f + axis) = 1.0;
    EXPECT_LT((result.hessian * v).norm(), 1e-8 * result.hessian.norm());
  }
  // With frame 0 fixed the problem is well posed: positive definite.
  const Eigen::MatrixXd fixed = result.hessian.bottomRightCorner(n - 6, n - 6);
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(fixed).eigenvalues();
  EXPECT_GT(eig(0), 1e-6 * eig(eig.size() - 1));
}

TEST(WindowBa, ReportsPlanePointsPerFrame) {
  const auto window = makeSyntheticWindow(SyntheticWindowSpec{});
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, syntheticSettings());
  ASSERT_EQ(result.plane_point_indices.size(), window.scans.size());
  std::size_t total = 0;
  for (std::size_t f = 0; f < window.scans.size(); ++f) {
    const auto& idx = result.plane_point_indices[f];
    EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
    EXPECT_TRUE(std::adjacent_find(idx.begin(), idx.end()) == idx.end());
    if (!idx.empty()) {
      EXPECT_LT(idx.back(), window.scans[f].size());
    }
    total += idx.size();
  }
  EXPECT_EQ(total, result.num_plane_points);
  EXPECT_EQ(result.plane_rms_initial.size(), result.num_planes);
  EXPECT_EQ(result.plane_rms_final.size(), result.num_planes);
}

TEST(WindowBa, WindowWithoutPlanesIsReturnedUnchanged) {
  // Scattered points: no voxel is planar.
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-10.f, 10.f);
  std::vector<PointCloud> scans(3);
  for (PointCloud& scan : scans) {
    for (int k = 0; k < 300; ++k) scan.add(Vec3f(u(rng), u(rng), u(rng)));
  }
  scans.emplace_back();  // and an empty scan
  const std::vector<const PointCloud*> ptrs = {&scans[0], &scans[1], &scans[2], &scans[3]};
  const std::vector<Pose> poses = test::randomPoses(rng, 4, 1.0);
  const BaResult result = optimizeWindow(ptrs, poses, BaSettings{});
  EXPECT_EQ(result.num_planes, 0u);
  EXPECT_EQ(result.final_cost, 0.0);
  ASSERT_EQ(result.hessian.rows(), 24);
  EXPECT_TRUE(result.hessian.isZero(0.0));
  for (std::size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(result.poses[i].t, poses[i].t);
}

TEST(WindowBa, SingleFrameAndIdenticalFramesStayFinite) {
  const auto window = makeSyntheticWindow(SyntheticWindowSpec{});
  const BaResult single =
      optimizeWindow({window.scanPointers()[0]}, {window.initial[0]}, syntheticSettings());
  EXPECT_EQ(single.num_planes, 0u);  // a plane needs two frames
  EXPECT_EQ(single.hessian.rows(), 6);
  EXPECT_TRUE(single.hessian.allFinite());

  // The same scan three times at the same pose: already consistent.
  const PointCloud* scan = window.scanPointers()[0];
  const BaResult same =
      optimizeWindow({scan, scan, scan}, std::vector<Pose>(3, window.truth[0]), syntheticSettings());
  EXPECT_GT(same.num_planes, 0u);
  EXPECT_TRUE(same.hessian.allFinite());
  EXPECT_LE(same.final_cost, same.last_association_initial_cost);
  for (const Pose& p : same.poses) EXPECT_TRUE(p.t.allFinite() && p.q.coeffs().allFinite());
}

TEST(WindowBa, EmptyWindowAndBadInput) {
  const BaResult empty = optimizeWindow({}, {}, BaSettings{});
  EXPECT_TRUE(empty.poses.empty());
  EXPECT_EQ(empty.num_planes, 0u);

  PointCloud scan;
  EXPECT_THROW(optimizeWindow({&scan}, {}, BaSettings{}), Error);
  EXPECT_THROW(optimizeWindow({nullptr}, {Pose()}, BaSettings{}), Error);
  BaSettings bad;
  bad.planes.voxel_size = 0.0;
  EXPECT_THROW(optimizeWindow({&scan}, {Pose()}, bad), Error);
}

TEST(LevenbergMarquardt, NeverIncreasesTheCost) {
  // Far from the optimum (large pose errors, fixed association): every
  // accepted step must lower the cost.
  std::mt19937 rng(17);
  const std::vector<Pose> truth = test::randomPoses(rng, 4, 2.0);
  std::vector<PlaneObservation> planes;
  for (int p = 0; p < 6; ++p)
    planes.push_back(test::randomPlane(rng, truth, {0, 1, 2, 3}, 30, 0.02).observation);
  const PlaneProblem problem(planes, 4);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<Pose> poses = truth;
    for (std::size_t i = 1; i < poses.size(); ++i) {
      poses[i] = Pose(Mat3(so3Exp(0.3 * test::randomUnit(rng)) * poses[i].R()),
                      Vec3(poses[i].t + 1.0 * test::randomUnit(rng)));
    }
    double previous = problem.cost(poses);
    for (int step = 0; step < 5; ++step) {
      const LmSummary s = solveLevenbergMarquardt(problem, poses, LmSettings{1, 0.0});
      EXPECT_LE(s.final_cost, previous);
      EXPECT_EQ(s.final_cost, problem.cost(poses));
      previous = s.final_cost;
    }
  }
}

}  // namespace
}  // namespace hba::ba
