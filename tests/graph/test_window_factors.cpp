#include <gtest/gtest.h>

#include <random>
#include <set>

#include "anchored_covariance.hpp"
#include "clamped_inverse.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/graph/window_factors.hpp"

namespace hba::graph {
namespace {

using test::randomPose;
using test::randomVec6;

struct Window {
  std::vector<Pose> poses;
  Eigen::MatrixXd hessian;
};

// K frames whose Hessian comes from relative measurements between all pairs.
Window makeWindow(std::mt19937& rng, std::size_t count) {
  Window w;
  for (std::size_t k = 0; k < count; ++k) w.poses.push_back(randomPose(rng, 5.0, 0.5));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) pairs.emplace_back(i, j);
  }
  Vec6 weights;
  weights << 400.0, 300.0, 200.0, 5e4, 4e4, 3e4;
  w.hessian = test::pairwiseHessian(w.poses, pairs, Mat6(weights.asDiagonal()));
  return w;
}

std::set<std::pair<std::size_t, std::size_t>> nodePairs(const std::vector<RelativePoseFactor>& fs) {
  std::set<std::pair<std::size_t, std::size_t>> out;
  for (const RelativePoseFactor& f : fs) out.emplace(f.from, f.to);
  return out;
}

// Window frame k at node 2k: the odd nodes between are in no factor.
std::vector<std::size_t> evenNodes(std::size_t count) {
  std::vector<std::size_t> nodes(count);
  for (std::size_t k = 0; k < count; ++k) nodes[k] = 2 * k;
  return nodes;
}

// The window's poses at its nodes, all but the first disturbed.
std::vector<Pose> disturbedStart(const Window& w, const std::vector<std::size_t>& nodes, std::mt19937& rng) {
  std::vector<Pose> initial(nodes.back() + 1);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    initial[nodes[k]] = k == 0 ? w.poses[0] : w.poses[k] * se3Exp(randomVec6(rng, 0.5, 0.1));
  }
  return initial;
}

// Solving `graph` (one window's factors) from `initial` must bring the
// window's optimized poses back exactly (its first frame holds the gauge).
void expectShapeRestored(const Window& w, const std::vector<std::size_t>& nodes,
                         const std::vector<Pose>& initial, const FactorGraph& graph) {
  PoseGraphSettings settings;
  settings.function_tolerance = 1e-16;
  const PoseGraphResult result = optimizeFactorGraph(initial, graph, settings);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    EXPECT_LT((result.poses[nodes[k]].t - w.poses[k].t).norm(), 1e-6) << k;
    EXPECT_LT(result.poses[nodes[k]].q.angularDistance(w.poses[k].q), 1e-6) << k;
  }
}

TEST(WindowFactors, PairChoicesMapWindowFramesToLayerOneNodes) {
  std::mt19937 rng(31);
  const Window w = makeWindow(rng, 4);
  const std::vector<std::size_t> nodes = {0, 9, 18, 27};  // frames of layer 3 with s = 3

  using Pairs = std::set<std::pair<std::size_t, std::size_t>>;
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::Adjacent)),
            (Pairs{{0, 9}, {9, 18}, {18, 27}}));
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::FromFirst)),
            (Pairs{{0, 9}, {0, 18}, {0, 27}}));
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::AllPairs)),
            (Pairs{{0, 9}, {0, 18}, {0, 27}, {9, 18}, {9, 27}, {18, 27}}));
}

TEST(WindowFactors, MeasurementsAndInformationMatchThePerPairFunctions) {
  std::mt19937 rng(32);
  const Window w = makeWindow(rng, 5);
  const std::vector<std::size_t> nodes = {10, 11, 12, 13, 14};
  const auto factors = windowFactors(w.hessian, w.poses, nodes, FactorPairs::AllPairs);
  ASSERT_EQ(factors.size(), 10u);
  for (const RelativePoseFactor& f : factors) {
    const std::size_t a = f.from - 10;
    const std::size_t b = f.to - 10;
    const Pose expected = relative(w.poses[a], w.poses[b]);
    EXPECT_LT((f.measurement.t - expected.t).norm(), 1e-12);
    EXPECT_LT(f.measurement.q.angularDistance(expected.q), 1e-12);
    const Mat6 information = relativePoseInformation(w.hessian, w.poses, a, b);
    EXPECT_LT((f.information - information).norm(), 1e-9 * information.norm());
  }
}

TEST(WindowFactors, PoseGraphOfAWindowRestoresItsOptimizedShape) {
  // Factors from one window, initial poses disturbed: the graph must bring the
  // window's relative poses back exactly (first frame fixed).
  std::mt19937 rng(33);
  const Window w = makeWindow(rng, 6);
  const std::vector<std::size_t> nodes = evenNodes(6);
  const std::vector<Pose> initial = disturbedStart(w, nodes, rng);
  for (const FactorPairs pairs : {FactorPairs::Adjacent, FactorPairs::AllPairs}) {
    FactorGraph graph(windowFactors(w.hessian, w.poses, nodes, pairs));
    expectShapeRestored(w, nodes, initial, graph);
  }
}

TEST(WindowShapeFactor, ItsCostIsTheWindowsSecondOrderCostModel) {
  // The window's cost near its optimum is (1/2) d^T H d; as a negative
  // log-likelihood (cost / 2 sigma^2), times 2 for e^T Omega e: d^T F d with
  // F = H / (2 sigma^2). The joint factor must give that for any small move
  // of the frames, the gauge frame's included (both ignore a rigid motion).
  std::mt19937 rng(35);
  const Window w = makeWindow(rng, 5);
  const std::vector<std::size_t> nodes = {0, 1, 2, 3, 4};
  const InformationSettings settings;
  const WindowShapeFactor shape = windowShapeFactor(w.hessian, w.poses, nodes, settings);
  ASSERT_EQ(shape.relative.size(), 4u);
  ASSERT_EQ(shape.information.rows(), 24);
  FactorGraph graph;
  graph.add(shape);
  const Eigen::MatrixXd fisher = w.hessian / (2.0 * settings.point_sigma * settings.point_sigma);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd d(30);
    std::vector<Pose> moved = w.poses;
    for (std::size_t k = 0; k < 5; ++k) {
      const Vec6 dk = randomVec6(rng, 1e-4, 1e-5);
      d.segment<6>(static_cast<Eigen::Index>(6 * k)) = dk;
      moved[k] = test::perturbWorld(w.poses[k], dk);
    }
    const double expected = d.dot(fisher * d);
    const double cost = factorGraphCost(moved, graph);
    EXPECT_NEAR(cost, expected, 1e-3 * expected) << trial;
  }
}

TEST(WindowShapeFactor, OfTwoFramesIsTheirRelativeFactor) {
  std::mt19937 rng(36);
  const Window w = makeWindow(rng, 2);
  const WindowShapeFactor shape = windowShapeFactor(w.hessian, w.poses, {7, 3});
  const auto pair = windowFactors(w.hessian, w.poses, {7, 3}, FactorPairs::Adjacent);
  ASSERT_EQ(pair.size(), 1u);
  EXPECT_EQ(shape.nodes, (std::vector<std::size_t>{7, 3}));
  EXPECT_LT((shape.relative[0].t - pair[0].measurement.t).norm(), 1e-12);
  EXPECT_LT((shape.information - pair[0].information).norm(), 1e-9 * pair[0].information.norm());
  EXPECT_TRUE(windowFactors(w.hessian, w.poses, {7, 3}, FactorPairs::Joint).empty());
}

TEST(WindowShapeFactor, PoseGraphOfAWindowRestoresItsOptimizedShape) {
  std::mt19937 rng(37);
  // 14 frames: the solver takes the factor in pieces of rows.
  for (const std::size_t count : {6, 14}) {
    const Window w = makeWindow(rng, count);
    const std::vector<std::size_t> nodes = evenNodes(count);
    FactorGraph graph;
    graph.add(windowShapeFactor(w.hessian, w.poses, nodes));
    expectShapeRestored(w, nodes, disturbedStart(w, nodes, rng), graph);
  }
}

TEST(WindowShapeFactor, InPiecesOrWholeTheGraphEndsAlike) {
  // A robust loss needs the whole residual; Huber this wide stays quadratic,
  // so both solve the same problem, one in pieces, one whole.
  std::mt19937 rng(38);
  const Window w = makeWindow(rng, 20);
  const std::vector<std::size_t> nodes = evenNodes(20);
  FactorGraph graph;
  graph.add(windowShapeFactor(w.hessian, w.poses, nodes));
  const std::vector<Pose> initial = disturbedStart(w, nodes, rng);
  PoseGraphSettings pieces;
  pieces.normal_equations = false;  // Ceres' pieces, against its whole residual
  pieces.max_iterations = 3;        // not converged: the paths themselves must agree
  PoseGraphSettings whole = pieces;
  whole.robust_loss = RobustLoss::Huber;
  whole.robust_loss_scale = 1e12;
  const PoseGraphResult a = optimizeFactorGraph(initial, graph, pieces);
  const PoseGraphResult b = optimizeFactorGraph(initial, graph, whole);
  EXPECT_NEAR(a.final_cost, b.final_cost, 1e-9 * (1.0 + b.final_cost));
  for (const std::size_t node : nodes) {
    EXPECT_LT((a.poses[node].t - b.poses[node].t).norm(), 1e-9) << node;
    EXPECT_LT(a.poses[node].q.angularDistance(b.poses[node].q), 1e-9) << node;
  }
}

// The information of the errors e_k (frame k from frame 0) is, by its
// definition, the inverse of their covariance J C J^T, C the frames'
// clamped covariance with frame 0 held and J_k = d e_k / d frame k. The
// factor forms it from the raised Hessian instead, without inverting
// twice; both must agree, also where weak directions are raised.
Eigen::MatrixXd informationFromTheCovariance(const Window& w, const InformationSettings& settings) {
  const auto covariance = anchoredCovariance(w.hessian, kGaugeFrame, settings);
  const std::size_t frames = w.poses.size() - 1;
  const auto size = static_cast<Eigen::Index>(6 * frames);
  Eigen::MatrixXd error_covariance(size, size);
  std::vector<Mat6> jacobians;
  for (std::size_t k = 1; k <= frames; ++k) {
    jacobians.push_back(
        relativePoseErrorJacobians(relative(w.poses[0], w.poses[k]), w.poses[0], w.poses[k]).d_to);
  }
  for (std::size_t i = 0; i < frames; ++i) {
    for (std::size_t j = 0; j < frames; ++j) {
      const auto row = static_cast<Eigen::Index>(6 * i);
      const auto col = static_cast<Eigen::Index>(6 * j);
      error_covariance.block<6, 6>(row, col) =
          jacobians[i] * covariance->block<6, 6>(row, col) * jacobians[j].transpose();
    }
  }
  return *clampedInverse(error_covariance, settings.min_eigen_ratio);
}

TEST(WindowShapeFactor, IsTheInverseOfTheErrorsCovarianceAlsoWhereWeakDirectionsAreRaised) {
  std::mt19937 rng(39);
  const InformationSettings settings;
  for (const double along_x : {400.0, 1e-9, 0.0}) {  // a corridor along every frame's x at the last two
    Window w = makeWindow(rng, 12);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i + 1 < w.poses.size(); ++i) pairs.emplace_back(i, i + 1);
    Vec6 weights;
    weights << along_x, 300.0, 200.0, 5e4, 4e4, 3e4;
    w.hessian = test::pairwiseHessian(w.poses, pairs, Mat6(weights.asDiagonal()));
    const Eigen::MatrixXd expected = informationFromTheCovariance(w, settings);
    const WindowShapeFactor shape = windowShapeFactor(w.hessian, w.poses, evenNodes(12), settings);
    EXPECT_LT((shape.information - expected).norm(), 1e-8 * expected.norm()) << along_x;
    EXPECT_LT((shape.information - shape.information.transpose()).norm(), 1e-12 * expected.norm());
  }
}

TEST(WindowShapeFactor, RejectsInconsistentArgumentsAndBadFactors) {
  std::mt19937 rng(38);
  const Window w = makeWindow(rng, 3);
  EXPECT_THROW(windowShapeFactor(w.hessian, w.poses, {0, 1}), Error);
  EXPECT_THROW(windowShapeFactor(w.hessian, w.poses, {0, 4, 4}), Error);
  const std::vector<Pose> poses(5);
  auto solve = [&poses](const WindowShapeFactor& f) {
    FactorGraph graph;
    graph.add(f);
    return optimizeFactorGraph(poses, graph, PoseGraphSettings{});
  };
  const WindowShapeFactor good = windowShapeFactor(w.hessian, w.poses, {0, 1, 2});
  WindowShapeFactor repeated = good;
  repeated.nodes = {0, 1, 1};
  EXPECT_THROW(solve(repeated), Error);
  WindowShapeFactor outside = good;
  outside.nodes = {0, 1, 5};
  EXPECT_THROW(solve(outside), Error);
  WindowShapeFactor short_measurements = good;
  short_measurements.relative.pop_back();
  EXPECT_THROW(solve(short_measurements), Error);
  WindowShapeFactor wrong_size = good;
  wrong_size.information = Eigen::MatrixXd::Identity(6, 6);
  EXPECT_THROW(solve(wrong_size), Error);
  WindowShapeFactor negative = good;
  negative.information = -Eigen::MatrixXd::Identity(12, 12);
  EXPECT_THROW(solve(negative), Error);
}

TEST(WindowFactors, RejectsInconsistentArguments) {
  std::mt19937 rng(34);
  const Window w = makeWindow(rng, 3);
  EXPECT_THROW(windowFactors(w.hessian, w.poses, {0, 1}, FactorPairs::Adjacent), Error);
  EXPECT_THROW(windowFactors(w.hessian, w.poses, {0, 4, 4}, FactorPairs::Adjacent), Error);
  const std::vector<Pose> too_few(w.poses.begin(), w.poses.begin() + 2);
  EXPECT_THROW(windowFactors(w.hessian, too_few, {0, 1}, FactorPairs::Adjacent), Error);
}

}  // namespace
}  // namespace hba::graph
