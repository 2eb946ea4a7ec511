#include "hba/graph/pose_graph.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <thread>

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "gauge_anchors.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "pose_block.hpp"
#include "relative_pose_cost.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

void validate(const std::vector<Pose>& initial, const std::vector<RelativePoseFactor>& factors,
              const PoseGraphSettings& settings) {
  for (std::size_t i = 0; i < initial.size(); ++i) {
    if (!initial[i].t.allFinite() || !initial[i].q.coeffs().allFinite()) {
      throw Error("pose graph: initial pose " + std::to_string(i) + " is not finite");
    }
  }
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const RelativePoseFactor& f = factors[k];
    const std::string name = "pose graph: factor " + std::to_string(k);
    if (f.from >= initial.size() || f.to >= initial.size()) {
      throw Error(name + " links node " + std::to_string(std::max(f.from, f.to)) +
                  " but there are " + std::to_string(initial.size()) + " poses");
    }
    if (f.from == f.to) throw Error(name + " links node " + std::to_string(f.from) + " to itself");
    if (!f.measurement.t.allFinite() || !f.measurement.q.coeffs().allFinite()) {
      throw Error(name + " has a non-finite measurement");
    }
  }
  if (settings.max_iterations < 0) throw Error("pose graph: max_iterations must be >= 0");
  if (settings.threads < 0) throw Error("pose graph: threads must be >= 0");
  if (!(settings.function_tolerance >= 0.0)) {
    throw Error("pose graph: function_tolerance must be >= 0");
  }
  if (settings.robust_loss != RobustLoss::None && !(settings.robust_loss_scale > 0.0)) {
    throw Error("pose graph: robust_loss_scale must be positive");
  }
}

std::unique_ptr<ceres::LossFunction> makeLoss(const PoseGraphSettings& settings) {
  switch (settings.robust_loss) {
    case RobustLoss::Huber:
      return std::make_unique<ceres::HuberLoss>(settings.robust_loss_scale);
    case RobustLoss::Cauchy:
      return std::make_unique<ceres::CauchyLoss>(settings.robust_loss_scale);
    case RobustLoss::None:
      break;
  }
  return nullptr;
}

int threadCount(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

ceres::Solver::Options solverOptions(const PoseGraphSettings& settings) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = settings.max_iterations;
  options.function_tolerance = settings.function_tolerance;
  options.num_threads = threadCount(settings.threads);
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

}  // namespace

PoseGraphResult optimizePoseGraph(const std::vector<Pose>& initial,
                                  const std::vector<RelativePoseFactor>& factors,
                                  const PoseGraphSettings& settings) {
  validate(initial, factors, settings);
  PoseGraphResult result;
  result.poses = initial;
  if (factors.empty()) {
    result.converged = true;
    return result;
  }

  std::vector<PoseBlock> blocks(initial.size());
  std::vector<bool> touched(initial.size(), false);
  for (std::size_t i = 0; i < initial.size(); ++i) blocks[i] = toPoseBlock(initial[i]);

  // The problem borrows the manifold and the loss; it owns the costs.
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  WorldPoseManifold manifold;
  const std::unique_ptr<ceres::LossFunction> loss = makeLoss(settings);

  for (const RelativePoseFactor& f : factors) {
    problem.AddResidualBlock(
        new RelativePoseCost(f.measurement, squareRootInformation(f.information)), loss.get(),
        blocks[f.from].data(), blocks[f.to].data());
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

  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(settings), &problem, &summary);

  // Ceres' cost is 1/2 sum rho(|S e|^2); report the pose graph's sum.
  result.initial_cost = 2.0 * summary.initial_cost;
  result.final_cost = 2.0 * summary.final_cost;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  // Copy back only what moved, so fixed and untouched poses stay bit-identical.
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (touched[i] && !fixed[i]) result.poses[i] = poseFromBlock(blocks[i].data());
  }
  return result;
}

double poseGraphCost(const std::vector<Pose>& poses,
                     const std::vector<RelativePoseFactor>& factors) {
  double cost = 0.0;
  for (const RelativePoseFactor& f : factors) {
    if (f.from >= poses.size() || f.to >= poses.size()) {
      throw Error("pose graph: factor links a node outside the " + std::to_string(poses.size()) +
                  " poses");
    }
    const Vec6 e = relativePoseError(f.measurement, poses[f.from], poses[f.to]);
    cost += e.dot(f.information * e);
  }
  return cost;
}

}  // namespace hba::graph
