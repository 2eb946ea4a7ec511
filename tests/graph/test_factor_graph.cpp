// Solving graphs with loop closures and priors: the gauge follows from the
// priors, loops close drift, and relative-only graphs solve exactly as before.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "gauge_anchors.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/graph/pose_graph.hpp"
#include "pose_block.hpp"
#include "relative_pose_cost.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

using test::randomVec6;

// A winding path of `n` poses heading along it, with some climb.
std::vector<Pose> windingPath(int n) {
  std::vector<Pose> poses;
  for (int i = 0; i < n; ++i) {
    const double s = i;
    const Vec3 position(2.0 * s, 12.0 * std::sin(s / 9.0), 0.5 * std::sin(s / 5.0));
    poses.emplace_back(so3Exp(Vec3(0.0, 0.0, 0.6 * std::cos(s / 9.0))), position);
  }
  return poses;
}

// A closed loop of `n` poses on a circle, heading along it.
std::vector<Pose> circle(int n, double radius) {
  std::vector<Pose> poses;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    poses.emplace_back(so3Exp(Vec3(0.0, 0.0, angle + M_PI / 2)),
                       Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.0));
  }
  return poses;
}

Mat6 odometryInformation() {
  Vec6 sigma;
  sigma << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005;
  return sigma.cwiseInverse().cwiseAbs2().asDiagonal();
}

// Odometry (i, i+1) that drifts: every step turns a little too far left and
// runs a little too long.
std::vector<RelativePoseFactor> driftingOdometry(const std::vector<Pose>& truth) {
  Vec6 bias;
  bias << 0.03, 0.0, 0.0, 0.0, 0.0, 0.004;
  std::vector<RelativePoseFactor> factors;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    factors.push_back({i, i + 1, relative(truth[i], truth[i + 1]) * se3Exp(bias), odometryInformation()});
  }
  return factors;
}

std::vector<Pose> deadReckoning(const Pose& start, const std::vector<RelativePoseFactor>& odometry) {
  std::vector<Pose> poses = {start};
  for (const RelativePoseFactor& f : odometry) poses.push_back(poses.back() * f.measurement);
  return poses;
}

double meanPositionError(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i].t - b[i].t).norm();
  return sum / static_cast<double>(a.size());
}

bool samePose(const Pose& a, const Pose& b) { return a.t == b.t && a.q.coeffs() == b.q.coeffs(); }

FactorGraph relativeGraph(const std::vector<RelativePoseFactor>& factors) { return FactorGraph(factors); }

TEST(FactorGraph, PositionPriorsPullADriftingChainBackWithNoNodeHeld) {
  const std::vector<Pose> truth = windingPath(60);
  const std::vector<RelativePoseFactor> odometry = driftingOdometry(truth);
  // Odometry also started from a wrong pose: node 0 itself must move.
  const Pose wrong_start = truth[0] * se3Exp((Vec6() << 1.5, -1.0, 0.4, 0, 0, 0.05).finished());
  const std::vector<Pose> initial = deadReckoning(wrong_start, odometry);

  FactorGraph graph = relativeGraph(odometry);
  std::mt19937 rng(41);
  std::normal_distribution<double> noise(0.0, 0.1);
  for (std::size_t i = 0; i < truth.size(); i += 5) {
    const Vec3 measured = truth[i].t + Vec3(noise(rng), noise(rng), noise(rng));
    graph.add(PositionPriorFactor{i, measured, Mat3::Identity() / (0.1 * 0.1)});
  }
  const PoseGraphResult result = optimizeFactorGraph(initial, graph);
  EXPECT_TRUE(result.converged);
  EXPECT_TRUE(result.held_nodes.empty());
  EXPECT_TRUE(result.orientation_held_nodes.empty());
  EXPECT_FALSE(samePose(result.poses[0], initial[0]));
  EXPECT_LT((result.poses[0].t - truth[0].t).norm(), 0.2 * (initial[0].t - truth[0].t).norm());
  const double odometry_error = meanPositionError(initial, truth);
  const double solved_error = meanPositionError(result.poses, truth);
  EXPECT_LT(solved_error, 0.1 * odometry_error)
      << "odometry " << odometry_error << " solved " << solved_error;
  EXPECT_NEAR(result.final_cost, factorGraphCost(result.poses, graph), 1e-9 * result.final_cost);
}

TEST(FactorGraph, PosePriorPlacesTheWholeGraphWithNoNodeHeld) {
  const std::vector<Pose> truth = windingPath(20);
  std::vector<RelativePoseFactor> exact;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    exact.push_back({i, i + 1, relative(truth[i], truth[i + 1]), Mat6::Identity()});
  }
  std::mt19937 rng(42);
  std::vector<Pose> initial = truth;
  for (Pose& p : initial) p = p * se3Exp(randomVec6(rng, 0.5, 0.05));
  FactorGraph graph = relativeGraph(exact);
  graph.add(PosePriorFactor{7, truth[7], 100.0 * Mat6::Identity()});
  PoseGraphSettings settings;
  settings.function_tolerance = 1e-16;
  const PoseGraphResult result = optimizeFactorGraph(initial, graph, settings);
  EXPECT_TRUE(result.held_nodes.empty());
  EXPECT_TRUE(result.orientation_held_nodes.empty());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT((result.poses[i].t - truth[i].t).norm(), 1e-6) << i;
    EXPECT_LT(result.poses[i].q.angularDistance(truth[i].q), 1e-6) << i;
  }
}

TEST(FactorGraph, OnePositionPriorMovesTheGraphButHoldsTheSmallestNodesOrientation) {
  const std::vector<Pose> truth = windingPath(15);
  std::vector<RelativePoseFactor> exact;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    exact.push_back({i, i + 1, relative(truth[i], truth[i + 1]), Mat6::Identity()});
  }
  // The start is the truth moved rigidly; node 15 is touched by nothing and
  // nodes 16-17 form a second component without priors.
  const Pose motion(so3Exp(Vec3(0.0, 0.1, 0.3)), Vec3(4.0, -3.0, 1.0));
  std::vector<Pose> initial;
  for (const Pose& p : truth) initial.push_back(motion * p);
  initial.push_back(Pose(so3Exp(Vec3(0.2, 0.0, 0.0)), Vec3(90, 90, 90)));
  initial.push_back(Pose(Quat::Identity(), Vec3(50, 0, 0)));
  initial.push_back(Pose(Quat::Identity(), Vec3(52, 0, 0)));
  FactorGraph graph = relativeGraph(exact);
  graph.add(RelativePoseFactor{16, 17, Pose(Quat::Identity(), Vec3(1, 0, 0)), Mat6::Identity()});
  graph.add(PositionPriorFactor{6, truth[6].t, Mat3::Identity()});

  PoseGraphSettings settings;
  settings.function_tolerance = 1e-16;
  const PoseGraphResult result = optimizeFactorGraph(initial, graph, settings);
  EXPECT_EQ(result.orientation_held_nodes, (std::vector<std::size_t>{0}));
  EXPECT_EQ(result.held_nodes, (std::vector<std::size_t>{16}));
  // Node 0 keeps its rotation bit for bit but moves; the prior is met and the
  // chain keeps its shape.
  EXPECT_EQ(result.poses[0].q.coeffs(), initial[0].q.coeffs());
  EXPECT_GT((result.poses[0].t - initial[0].t).norm(), 1.0);
  EXPECT_LT((result.poses[6].t - truth[6].t).norm(), 1e-6);
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    const Pose step = relative(result.poses[i], result.poses[i + 1]);
    EXPECT_LT((step.t - exact[i].measurement.t).norm(), 1e-6) << i;
  }
  EXPECT_TRUE(samePose(result.poses[15], initial[15]));
  EXPECT_TRUE(samePose(result.poses[16], initial[16]));
  EXPECT_LT((result.poses[17].t - Vec3(51, 0, 0)).norm(), 1e-6);
}

TEST(FactorGraph, ALoopClosureClosesADriftingLoop) {
  const std::vector<Pose> truth = circle(60, 25.0);
  const std::vector<RelativePoseFactor> odometry = driftingOdometry(truth);
  const std::vector<Pose> initial = deadReckoning(truth[0], odometry);
  FactorGraph graph = relativeGraph(odometry);
  // Without the loop the odometry is already consistent: nothing moves.
  const PoseGraphResult open = optimizeFactorGraph(initial, graph);
  EXPECT_LT(meanPositionError(open.poses, initial), 1e-6);

  graph.add(LoopClosureFactor{59, 0, relative(truth[59], truth[0]), odometryInformation()});
  EXPECT_EQ(graph.count("loop closure"), 1u);
  EXPECT_EQ(graph.count("relative"), odometry.size());
  const PoseGraphResult closed = optimizeFactorGraph(initial, graph);
  EXPECT_TRUE(closed.converged);
  EXPECT_EQ(closed.held_nodes, (std::vector<std::size_t>{0}));
  const double odometry_error = meanPositionError(initial, truth);
  const double closed_error = meanPositionError(closed.poses, truth);
  EXPECT_LT(closed_error, 0.3 * odometry_error)
      << "odometry " << odometry_error << " closed " << closed_error;
  // The loop's own end now meets its start.
  EXPECT_LT((relative(closed.poses[59], closed.poses[0]).t - relative(truth[59], truth[0]).t).norm(),
            0.5 * (relative(initial[59], initial[0]).t - relative(truth[59], truth[0]).t).norm());
}

// Identity rotations held stiff, so only translations trade (as in
// test_pose_graph.cpp).
Mat6 stiffRotation(double translation_weight) {
  Mat6 information = Mat6::Zero();
  information.diagonal() << translation_weight, translation_weight, translation_weight, 1e8, 1e8, 1e8;
  return information;
}

TEST(FactorGraph, LoopsHaveTheirOwnRobustLoss) {
  std::vector<Pose> initial;
  for (int i = 0; i < 6; ++i) initial.emplace_back(Quat::Identity(), Vec3(i, 0, 0));
  FactorGraph graph;
  for (std::size_t i = 0; i + 1 < 6; ++i) {
    graph.add(RelativePoseFactor{i, i + 1, Pose(Quat::Identity(), Vec3(1, 0, 0)), stiffRotation(100.0)});
  }
  graph.add(LoopClosureFactor{0, 5, Pose(Quat::Identity(), Vec3(8, 0, 0)),  // 3 m wrong
                              stiffRotation(100.0)});
  auto shift = [&](const PoseGraphSettings& settings) {
    return std::abs(optimizeFactorGraph(initial, graph, settings).poses[5].t.x() - 5.0);
  };
  const double plain = shift({});
  PoseGraphSettings loop_robust;
  loop_robust.loop_robust_loss = RobustLoss::Cauchy;
  PoseGraphSettings window_robust;
  window_robust.robust_loss = RobustLoss::Cauchy;
  EXPECT_GT(plain, 1.0);
  EXPECT_LT(shift(loop_robust), 0.1 * plain);
  // The window loss leaves the loop at full weight (and weakens the windows).
  EXPECT_GT(shift(window_robust), plain);
}

// Today's solver, rebuilt from its parts: the problem a relative-only graph
// must still produce, bit for bit.
std::vector<Pose> todaysSolve(const std::vector<Pose>& initial,
                              const std::vector<RelativePoseFactor>& factors) {
  std::vector<PoseBlock> blocks;
  for (const Pose& p : initial) blocks.push_back(toPoseBlock(p));
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  WorldPoseManifold manifold;
  std::vector<bool> touched(initial.size(), false);
  for (const RelativePoseFactor& f : factors) {
    problem.AddResidualBlock(new RelativePoseCost(f.measurement, squareRootInformation(f.information)),
                             nullptr, blocks[f.from].data(), blocks[f.to].data());
    touched[f.from] = touched[f.to] = true;
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (touched[i]) problem.SetManifold(blocks[i].data(), &manifold);
  }
  std::vector<bool> fixed(initial.size(), false);
  for (const std::size_t anchor : gaugeAnchors(initial.size(), factors)) {
    problem.SetParameterBlockConstant(blocks[anchor].data());
    fixed[anchor] = true;
  }
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = PoseGraphSettings{}.max_iterations;
  options.function_tolerance = PoseGraphSettings{}.function_tolerance;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  std::vector<Pose> poses = initial;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (touched[i] && !fixed[i]) poses[i] = poseFromBlock(blocks[i].data());
  }
  return poses;
}

TEST(FactorGraph, RelativeOnlyGraphsSolveBitForBitAsBefore) {
  const std::vector<Pose> truth = circle(80, 30.0);
  std::mt19937 rng(43);
  std::vector<RelativePoseFactor> factors = driftingOdometry(truth);
  for (std::size_t i = 0; i + 4 < truth.size(); i += 3) {
    factors.push_back({i, i + 4, relative(truth[i], truth[i + 4]) * se3Exp(randomVec6(rng, 0.05, 0.01)),
                       odometryInformation()});
  }
  factors.push_back({79, 0, relative(truth[79], truth[0]), odometryInformation()});
  // A second component, and node 80 that nothing touches.
  std::vector<Pose> initial = deadReckoning(truth[0], driftingOdometry(truth));
  for (int k = 0; k < 4; ++k) initial.push_back(Pose(Quat::Identity(), Vec3(100.0 + k, 0, 0)));
  factors.push_back({81, 82, Pose(Quat::Identity(), Vec3(2, 0, 0)), Mat6::Identity()});
  factors.push_back({83, 82, Pose(Quat::Identity(), Vec3(-1, 0.5, 0)), Mat6::Identity()});

  const std::vector<Pose> expected = todaysSolve(initial, factors);
  PoseGraphSettings settings;
  settings.threads = 1;
  settings.normal_equations = false;  // the Ceres solve, as before
  const PoseGraphResult wrapped = optimizePoseGraph(initial, factors, settings);
  const PoseGraphResult general = optimizeFactorGraph(initial, FactorGraph(factors), settings);
  EXPECT_EQ(wrapped.held_nodes, (std::vector<std::size_t>{0, 81}));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < initial.size(); ++i) {
    EXPECT_TRUE(samePose(wrapped.poses[i], expected[i])) << i;
    EXPECT_TRUE(samePose(general.poses[i], expected[i])) << i;
    moved += samePose(expected[i], initial[i]) ? 0 : 1;
  }
  EXPECT_EQ(moved, initial.size() - 3);  // all but the two held nodes and node 80
  EXPECT_EQ(poseGraphCost(initial, factors), factorGraphCost(initial, FactorGraph(factors)));
}

FactorGraph mixedGraph(const std::vector<Pose>& truth, const std::vector<Pose>& initial) {
  std::mt19937 rng(44);
  FactorGraph graph = FactorGraph(driftingOdometry(truth));
  graph.add(LoopClosureFactor{truth.size() - 1, 0,
                              relative(truth.back(), truth[0]) * se3Exp(randomVec6(rng, 0.1, 0.01)),
                              odometryInformation()});
  for (std::size_t i = 0; i < truth.size(); i += 7) {
    graph.add(PositionPriorFactor{i, truth[i].t + test::randomVec3(rng, 0.2), 25.0 * Mat3::Identity()});
  }
  graph.add(PosePriorFactor{3, initial[3], Mat6::Identity()});
  return graph;
}

TEST(FactorGraph, IsDeterministicWithOneThread) {
  const std::vector<Pose> truth = circle(50, 20.0);
  const std::vector<Pose> initial = deadReckoning(truth[0], driftingOdometry(truth));
  const FactorGraph graph = mixedGraph(truth, initial);
  PoseGraphSettings settings;
  settings.threads = 1;
  settings.loop_robust_loss = RobustLoss::Huber;
  const PoseGraphResult first = optimizeFactorGraph(initial, graph, settings);
  const PoseGraphResult second = optimizeFactorGraph(initial, graph, settings);
  EXPECT_GT(first.iterations, 0);
  EXPECT_EQ(first.final_cost, second.final_cost);
  EXPECT_EQ(first.iterations, second.iterations);
  for (std::size_t i = 0; i < initial.size(); ++i) {
    EXPECT_TRUE(samePose(first.poses[i], second.poses[i])) << i;
  }
}

// The message of the hba::Error that `call` throws ("" when it does not throw).
template <typename Call>
std::string errorOf(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FactorGraph, RejectsBadFactorsNamingTheirIndexAndKind) {
  const std::vector<Pose> initial(3);
  auto solve = [&](auto factor) {
    return errorOf([&] {
      FactorGraph graph;
      graph.add(RelativePoseFactor{0, 1, Pose(), Mat6::Identity()});
      graph.add(factor);
      optimizeFactorGraph(initial, graph);
    });
  };
  EXPECT_EQ(solve(PositionPriorFactor{3, Vec3::Zero(), Mat3::Identity()}),
            "pose graph: factor 1 (position prior) links node 3 but there are 3 poses");
  EXPECT_EQ(solve(PositionPriorFactor{1, Vec3(0, std::nan(""), 0), Mat3::Identity()}),
            "pose graph: factor 1 (position prior) has a non-finite position");
  EXPECT_EQ(solve(PositionPriorFactor{1, Vec3::Zero(), -Mat3::Identity()}),
            "pose graph: factor 1 (position prior): information is not positive semi-definite");
  EXPECT_EQ(solve(PosePriorFactor{5, Pose(), Mat6::Identity()}),
            "pose graph: factor 1 (pose prior) links node 5 but there are 3 poses");
  Pose nan_pose;
  nan_pose.t.x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(solve(PosePriorFactor{1, nan_pose, Mat6::Identity()}),
            "pose graph: factor 1 (pose prior) has a non-finite measurement");
  Mat6 nan_information = Mat6::Identity();
  nan_information(2, 4) = std::nan("");
  EXPECT_EQ(solve(PosePriorFactor{1, Pose(), nan_information}),
            "pose graph: factor 1 (pose prior): information is not finite");
  EXPECT_EQ(solve(LoopClosureFactor{2, 2, Pose(), Mat6::Identity()}),
            "pose graph: factor 1 (loop closure) links node 2 to itself");
  EXPECT_EQ(solve(LoopClosureFactor{0, 7, Pose(), Mat6::Identity()}),
            "pose graph: factor 1 (loop closure) links node 7 but there are 3 poses");
  Mat6 indefinite = Mat6::Identity();
  indefinite(5, 5) = -1.0;
  EXPECT_EQ(solve(LoopClosureFactor{0, 2, Pose(), indefinite}),
            "pose graph: factor 1 (loop closure): information is not positive semi-definite");
  EXPECT_EQ(solve(RelativePoseFactor{0, 2, nan_pose, Mat6::Identity()}),
            "pose graph: factor 1 (relative) has a non-finite measurement");
  // A positive semi-definite prior is fine (it just pins nothing).
  Mat3 vertical_only = Mat3::Zero();
  vertical_only(2, 2) = 1.0;
  EXPECT_EQ(solve(PositionPriorFactor{1, Vec3::Zero(), vertical_only}), "");

  FactorGraph out_of_range;
  out_of_range.add(PositionPriorFactor{4, Vec3::Zero(), Mat3::Identity()});
  EXPECT_THROW(factorGraphCost(initial, out_of_range), Error);
}

TEST(FactorGraph, RejectsBadGaugeAndLoopSettings) {
  const std::vector<Pose> initial(2);
  FactorGraph graph;
  graph.add(LoopClosureFactor{0, 1, Pose(), Mat6::Identity()});
  PoseGraphSettings loop_scale;
  loop_scale.loop_robust_loss = RobustLoss::Huber;
  loop_scale.loop_robust_loss_scale = 0.0;
  EXPECT_EQ(errorOf([&] { optimizeFactorGraph(initial, graph, loop_scale); }),
            "pose graph: loop_robust_loss_scale must be positive");
  for (const double spread : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    PoseGraphSettings settings;
    settings.min_prior_spread = spread;
    EXPECT_EQ(errorOf([&] { optimizeFactorGraph(initial, graph, settings); }),
              "pose graph: min_prior_spread must be positive and finite")
        << spread;
  }
}

}  // namespace
}  // namespace hba::graph
