// The pose graph's own normal equations (src/graph/normal_equations.cpp)
// and the Levenberg-Marquardt on them (tangent_solver.cpp): each factor's
// terms against finite differences and against its Ceres cost, and the
// solve against Ceres' on the same graphs.
#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <random>

#include <ceres/cost_function.h>

#include "factor_model.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/lie.hpp"
#include "hba/graph/factor_graph.hpp"
#include "hba/graph/pose_graph.hpp"
#include "normal_equations.hpp"

namespace hba::graph {
namespace {

using test::centralDifference;
using test::maxPoseError;
using test::perturbWorld;
using test::randomPose;
using test::randomVec6;

// A window of `frames` poses near a random start, its measured shape off
// by a little noise, and a random positive definite information.
WindowShapeFactor randomWindow(std::mt19937& rng, const std::vector<Pose>& poses,
                               const std::vector<std::size_t>& nodes) {
  WindowShapeFactor factor;
  factor.nodes = nodes;
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    factor.relative.push_back(relative(poses[nodes[0]], poses[nodes[k]]) *
                              se3Exp(randomVec6(rng, 0.05, 0.02)));
  }
  const auto n = static_cast<Eigen::Index>(6 * (nodes.size() - 1));
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd root(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) root(i, j) = normal(rng);
  factor.information = root.transpose() * root + 0.5 * Eigen::MatrixXd::Identity(n, n);
  return factor;
}

std::vector<Pose> chain(std::mt19937& rng, std::size_t count) {
  std::vector<Pose> poses{randomPose(rng)};
  for (std::size_t k = 1; k < count; ++k) poses.push_back(poses.back() * se3Exp(randomVec6(rng, 1.0, 0.1)));
  return poses;
}

// Every node variable.
std::unique_ptr<NormalEquations> systemFor(std::size_t poses, const std::vector<std::size_t>& nodes) {
  return std::make_unique<NormalEquations>(std::vector<bool>(poses, true),
                                           std::vector<std::vector<std::size_t>>{nodes});
}

TEST(NormalEquations, WindowShapeTermsAreThoseOfItsWhitenedResidualAndItsCostsSlope) {
  std::mt19937 rng(41);
  const std::vector<Pose> poses = chain(rng, 9);
  const std::vector<std::size_t> nodes = {2, 0, 5, 3, 8, 7};  // any order; node 0 of the window is 2
  const FactorModelPtr model = modelOf(randomWindow(rng, poses, nodes));
  ASSERT_TRUE(model->formsNormalEquations());

  const auto direct = systemFor(poses.size(), nodes);
  model->addNormalEquations(poses, *direct);
  const auto through_cost = systemFor(poses.size(), nodes);
  const std::unique_ptr<ceres::CostFunction> cost(model->newCost());
  addTermsFromCost(*cost, nodes, poses, *through_cost);

  EXPECT_NEAR(direct->cost(), model->cost(poses), 1e-9 * model->cost(poses));
  EXPECT_NEAR(through_cost->cost(), model->cost(poses), 1e-9 * model->cost(poses));
  const double scale = through_cost->hessian().cwiseAbs().maxCoeff();
  EXPECT_LT((direct->hessian() - through_cost->hessian()).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((direct->gradient() - through_cost->gradient()).cwiseAbs().maxCoeff(), 1e-9 * scale);
  // Nodes no factor links (1, 4, 6) have nothing.
  for (const Eigen::Index free_node : {1, 4, 6}) {
    const Eigen::MatrixXd block = direct->hessian().block(6 * free_node, 6 * free_node, 6, 6);
    EXPECT_EQ(block.norm(), 0.0) << free_node;
  }

  // The gradient is half the cost's slope along each tangent direction.
  // A 1x1 matrix, so that centralDifference's .eval() applies to a scalar too.
  const auto model_cost = [&](const std::vector<Pose>& p) {
    return Eigen::Matrix<double, 1, 1>(model->cost(p));
  };
  for (const std::size_t node : nodes) {
    for (int d = 0; d < 6; ++d) {
      const double slope = centralDifference(poses, node, d, 1e-6, model_cost)(0);
      EXPECT_NEAR(direct->gradient()[static_cast<Eigen::Index>(6 * node) + d], 0.5 * slope,
                  1e-5 * (1.0 + std::abs(slope)))
          << "node " << node << " direction " << d;
    }
  }
}

TEST(NormalEquations, HeldNodesHaveNoUnknownsAndEveryPairIsKeptOnce) {
  std::mt19937 rng(42);
  const std::vector<Pose> poses = chain(rng, 5);
  const std::vector<std::size_t> nodes = {1, 3, 4};
  std::vector<bool> variable(poses.size(), true);
  variable[3] = false;
  NormalEquations system(variable, {nodes, nodes});
  const FactorModelPtr model = modelOf(randomWindow(rng, poses, nodes));
  model->addNormalEquations(poses, system);
  // Unknowns: nodes 0, 1, 2, 4 (3 is held).
  EXPECT_EQ(system.hessian().rows(), 24);
  const auto full = systemFor(poses.size(), nodes);
  model->addNormalEquations(poses, *full);
  // Node 4 is the fourth unknown; its coupling to node 1 as with every node variable.
  EXPECT_LT((system.hessian().block<6, 6>(18, 6) - full->hessian().block<6, 6>(24, 6)).norm(),
            1e-12 * full->hessian().norm());
  EXPECT_EQ(system.gradient().segment<6>(0).norm(), 0.0);
}

// A graph of window shapes (windows of 8 frames every 4 over a chain) and
// two loops, from a start perturbed off the measured poses.
struct ShapeGraph {
  std::vector<Pose> start;
  FactorGraph graph;
};

ShapeGraph shapeGraph(unsigned seed) {
  std::mt19937 rng(seed);
  const std::vector<Pose> truth = chain(rng, 40);
  ShapeGraph out;
  for (std::size_t first = 0; first + 8 <= truth.size(); first += 4) {
    std::vector<std::size_t> nodes(8);
    std::iota(nodes.begin(), nodes.end(), first);
    out.graph.add(randomWindow(rng, truth, nodes));
  }
  for (const auto& [from, to] : {std::pair<std::size_t, std::size_t>{0, 39}, {10, 30}}) {
    LoopClosureFactor loop;
    loop.from = from;
    loop.to = to;
    loop.measurement = relative(truth[from], truth[to]) * se3Exp(randomVec6(rng, 0.02, 0.01));
    loop.information = 100.0 * Mat6::Identity();
    out.graph.add(loop);
  }
  out.start = truth;
  for (std::size_t k = 1; k < truth.size(); ++k)
    out.start[k] = perturbWorld(truth[k], randomVec6(rng, 0.5, 0.05));
  return out;
}

TEST(NormalEquations, TheSolveEndsAtTheMinimumAsCloseAsCeresDoes) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const ShapeGraph g = shapeGraph(seed);
    PoseGraphSettings ceres_solve;
    ceres_solve.normal_equations = false;
    PoseGraphSettings exact = ceres_solve;
    exact.last_step_gain = 0.0;
    exact.function_tolerance = 1e-16;
    const PoseGraphResult ours = optimizeFactorGraph(g.start, g.graph);
    const PoseGraphResult theirs = optimizeFactorGraph(g.start, g.graph, ceres_solve);
    const PoseGraphResult minimum = optimizeFactorGraph(g.start, g.graph, exact);
    EXPECT_TRUE(ours.converged) << seed;
    EXPECT_NEAR(ours.initial_cost, theirs.initial_cost, 1e-9 * theirs.initial_cost) << seed;
    EXPECT_LT(minimum.final_cost, 0.01 * minimum.initial_cost) << seed;
    EXPECT_NEAR(ours.final_cost, minimum.final_cost, 1e-9 * minimum.final_cost) << seed;
    // Within 1e-5 of the minimum (Ceres' default: 1.2e-6 to 3.1e-6 on these).
    EXPECT_LT(maxPoseError(ours.poses, minimum.poses), 1e-5) << seed;
    EXPECT_EQ(ours.held_nodes, theirs.held_nodes);
    EXPECT_EQ(ours.poses[0].t, g.start[0].t);  // the held node, bit for bit
  }
}

TEST(NormalEquations, RobustLossesAndHeldOrientationsAreLeftToCeres) {
  const ShapeGraph g = shapeGraph(4);
  PoseGraphSettings robust;
  robust.loop_robust_loss = RobustLoss::Cauchy;
  PoseGraphSettings robust_ceres = robust;
  robust_ceres.normal_equations = false;
  const PoseGraphResult a = optimizeFactorGraph(g.start, g.graph, robust);
  const PoseGraphResult b = optimizeFactorGraph(g.start, g.graph, robust_ceres);
  // The same solver: the same bits.
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t k = 0; k < a.poses.size(); ++k) {
    EXPECT_EQ(a.poses[k].t, b.poses[k].t) << k;
    EXPECT_EQ(a.poses[k].q.coeffs(), b.poses[k].q.coeffs()) << k;
  }
  EXPECT_EQ(a.iterations, b.iterations);
}

}  // namespace
}  // namespace hba::graph
