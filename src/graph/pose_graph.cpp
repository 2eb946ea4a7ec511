#include "hba/graph/pose_graph.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include <ceres/iteration_callback.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "factor_model.hpp"
#include "gauge_anchors.hpp"
#include "hba/core/error.hpp"
#include "orientation_held_manifold.hpp"
#include "pose_block.hpp"
#include "tangent_solver.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

void validate(const std::vector<Pose>& initial, const FactorGraph& factors,
              const PoseGraphSettings& settings) {
  for (std::size_t i = 0; i < initial.size(); ++i) {
    if (!initial[i].t.allFinite() || !initial[i].q.coeffs().allFinite()) {
      throw Error("pose graph: initial pose " + std::to_string(i) + " is not finite");
    }
  }
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const FactorModel& model = *factors.models()[k];
    model.validate(initial.size(), "pose graph: factor " + std::to_string(k) + " (" + model.name() + ")");
  }
  if (settings.max_iterations < 0) throw Error("pose graph: max_iterations must be >= 0");
  if (settings.threads < 0) throw Error("pose graph: threads must be >= 0");
  if (!(settings.function_tolerance >= 0.0)) {
    throw Error("pose graph: function_tolerance must be >= 0");
  }
  if (settings.robust_loss != RobustLoss::None && !(settings.robust_loss_scale > 0.0)) {
    throw Error("pose graph: robust_loss_scale must be positive");
  }
  if (settings.loop_robust_loss != RobustLoss::None && !(settings.loop_robust_loss_scale > 0.0)) {
    throw Error("pose graph: loop_robust_loss_scale must be positive");
  }
  if (settings.prior_robust_loss != RobustLoss::None && !(settings.prior_robust_loss_scale > 0.0)) {
    throw Error("pose graph: prior_robust_loss_scale must be positive");
  }
  if (!(settings.last_step_gain >= 0.0 && settings.last_step_gain < 1.0)) {
    throw Error("pose graph: last_step_gain must be in [0, 1)");
  }
  if (!(settings.min_prior_spread > 0.0) || !std::isfinite(settings.min_prior_spread)) {
    throw Error("pose graph: min_prior_spread must be positive and finite");
  }
}

std::unique_ptr<ceres::LossFunction> makeLoss(RobustLoss kind, double scale) {
  switch (kind) {
    case RobustLoss::Huber:
      return std::make_unique<ceres::HuberLoss>(scale);
    case RobustLoss::Cauchy:
      return std::make_unique<ceres::CauchyLoss>(scale);
    case RobustLoss::None:
      break;
  }
  return nullptr;
}

// Ends the solve after a taken step that gained less than `fraction` of
// the cost it started from (PoseGraphSettings::last_step_gain).
class LastStepGain final : public ceres::IterationCallback {
 public:
  explicit LastStepGain(double fraction) : fraction_(fraction) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& step) override {
    const bool small = step.cost_change < fraction_ * (step.cost + step.cost_change);
    if (step.iteration > 0 && step.step_is_successful && small) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  double fraction_;
};

ceres::Solver::Options solverOptions(const PoseGraphSettings& settings) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = settings.max_iterations;
  options.function_tolerance = settings.function_tolerance;
  // One thread: Ceres 2.2 (Debian 13) adds its threads' partial costs and
  // gradients in the order they finish, so on more than one the poses differ
  // in their last bits from run to run, and mpirun's members from one process
  // (HierarchicalBa.MembersOfAGroupGetThePosesOfOneProcess failed 5 runs in 12).
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

}  // namespace

namespace {

// Which nodes the factors touch, and which of those hold the gauge (also
// listed in `result`).
struct Gauge {
  std::vector<bool> touched;
  std::vector<bool> fixed;
  std::vector<bool> orientation_fixed;
};

Gauge chooseGauge(std::size_t poses, const FactorGraph& factors, const PoseGraphSettings& settings,
                  PoseGraphResult& result) {
  Gauge gauge{std::vector<bool>(poses, false), std::vector<bool>(poses, false),
              std::vector<bool>(poses, false)};
  std::vector<GaugeInput> inputs;
  inputs.reserve(factors.size());
  for (const auto& model : factors.models()) {
    inputs.push_back({model->nodes(), model->gaugePin()});
    for (const std::size_t node : inputs.back().nodes) gauge.touched[node] = true;
  }
  for (const GaugeAnchor& anchor : componentAnchors(poses, inputs, settings.min_prior_spread)) {
    if (anchor.hold == GaugeHold::Pose) {
      gauge.fixed[anchor.node] = true;
      result.held_nodes.push_back(anchor.node);
    } else {
      gauge.orientation_fixed[anchor.node] = true;
      result.orientation_held_nodes.push_back(anchor.node);
    }
  }
  return gauge;
}

void solveByNormalEquations(const std::vector<Pose>& initial, const FactorGraph& factors, const Gauge& gauge,
                            const PoseGraphSettings& settings, PoseGraphResult& result) {
  std::vector<bool> variable(initial.size());
  for (std::size_t i = 0; i < initial.size(); ++i) variable[i] = gauge.touched[i] && !gauge.fixed[i];
  TangentSolve solved = solveInTangent(initial, factors, variable, settings);
  result.poses = std::move(solved.poses);
  result.initial_cost = solved.initial_cost;
  result.final_cost = solved.final_cost;
  result.iterations = solved.iterations;
  result.converged = solved.converged;
}

void solveWithCeres(const std::vector<Pose>& initial, const FactorGraph& factors, const Gauge& gauge,
                    const PoseGraphSettings& settings, PoseGraphResult& result) {
  std::vector<PoseBlock> blocks(initial.size());
  for (std::size_t i = 0; i < initial.size(); ++i) blocks[i] = toPoseBlock(initial[i]);

  // The problem borrows the manifolds and the losses; it owns the costs.
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  WorldPoseManifold manifold;
  OrientationHeldManifold orientation_held;
  const std::unique_ptr<ceres::LossFunction> window_loss =
      makeLoss(settings.robust_loss, settings.robust_loss_scale);
  const std::unique_ptr<ceres::LossFunction> loop_loss =
      makeLoss(settings.loop_robust_loss, settings.loop_robust_loss_scale);
  const std::unique_ptr<ceres::LossFunction> prior_loss =
      makeLoss(settings.prior_robust_loss, settings.prior_robust_loss_scale);
  auto lossOf = [&](LossGroup group) -> ceres::LossFunction* {
    if (group == LossGroup::Window) return window_loss.get();
    if (group == LossGroup::Loop) return loop_loss.get();
    if (group == LossGroup::Prior) return prior_loss.get();
    return nullptr;
  };
  for (const auto& model : factors.models()) {
    const std::vector<std::size_t> nodes = model->nodes();
    ceres::LossFunction* loss = lossOf(model->lossGroup());
    for (CostPiece& piece : model->newCosts(loss != nullptr)) {
      std::vector<double*> parameters;
      for (const std::size_t k : piece.node_positions) parameters.push_back(blocks[nodes[k]].data());
      problem.AddResidualBlock(piece.cost.release(), loss, parameters);
    }
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!gauge.touched[i]) continue;
    problem.SetManifold(blocks[i].data(), gauge.orientation_fixed[i]
                                              ? static_cast<ceres::Manifold*>(&orientation_held)
                                              : &manifold);
  }
  for (const std::size_t node : result.held_nodes) problem.SetParameterBlockConstant(blocks[node].data());

  ceres::Solver::Options options = solverOptions(settings);
  LastStepGain last_step(settings.last_step_gain);
  if (settings.last_step_gain > 0.0) options.callbacks.push_back(&last_step);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  // Ceres' cost is 1/2 sum rho(|S e|^2); report the pose graph's sum.
  result.initial_cost = 2.0 * summary.initial_cost;
  result.final_cost = 2.0 * summary.final_cost;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.converged =
      summary.termination_type == ceres::CONVERGENCE || summary.termination_type == ceres::USER_SUCCESS;
  // Copy back only what moved, so fixed and untouched poses stay bit-identical.
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (gauge.touched[i] && !gauge.fixed[i]) result.poses[i] = poseFromBlock(blocks[i].data());
  }
}

}  // namespace

PoseGraphResult optimizeFactorGraph(const std::vector<Pose>& initial, const FactorGraph& factors,
                                    const PoseGraphSettings& settings) {
  validate(initial, factors, settings);
  PoseGraphResult result;
  result.poses = initial;
  if (factors.empty()) {
    result.converged = true;
    return result;
  }
  const Gauge gauge = chooseGauge(initial.size(), factors, settings, result);
  // Ours where it applies: no robust loss, whole poses held.
  const bool robust = settings.robust_loss != RobustLoss::None ||
                      settings.loop_robust_loss != RobustLoss::None ||
                      settings.prior_robust_loss != RobustLoss::None;
  if (settings.normal_equations && !robust && result.orientation_held_nodes.empty()) {
    solveByNormalEquations(initial, factors, gauge, settings, result);
  } else {
    solveWithCeres(initial, factors, gauge, settings, result);
  }
  return result;
}

PoseGraphResult optimizePoseGraph(const std::vector<Pose>& initial,
                                  const std::vector<RelativePoseFactor>& factors,
                                  const PoseGraphSettings& settings) {
  return optimizeFactorGraph(initial, FactorGraph(factors), settings);
}

double factorGraphCost(const std::vector<Pose>& poses, const FactorGraph& factors) {
  double cost = 0.0;
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const FactorModel& model = *factors.models()[k];
    for (const std::size_t node : model.nodes()) {
      checkNode(node, poses.size(), "pose graph: factor " + std::to_string(k) + " (" + model.name() + ")");
    }
    cost += model.cost(poses);
  }
  return cost;
}

double poseGraphCost(const std::vector<Pose>& poses, const std::vector<RelativePoseFactor>& factors) {
  return factorGraphCost(poses, FactorGraph(factors));
}

}  // namespace hba::graph
