#pragma once
// The top-down pose graph: all layer-1 poses as unknowns, relative-pose
// factors from the BA windows of every layer, optionally loop closures and
// priors. Solved by Levenberg-Marquardt on its normal equations with CHOLMOD
// (ours, tangent_solver.cpp) or, with robust losses, by Ceres.
// See docs/graph.md.
#include <cstddef>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"
#include "hba/graph/factor_graph.hpp"
#include "hba/graph/factors.hpp"

namespace hba::graph {

enum class RobustLoss { None, Huber, Cauchy };

struct PoseGraphSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-10;
  // A step that lowers the cost by less than this fraction of it is the
  // last: the solve ends converged with that step taken. Ceres' own
  // tolerances ask for one more factorization, whose step the poses do not
  // show (nclt's top-down graph: steps gaining 0.65, 1.2e-5 and 2e-8 of the
  // cost, then one of 4e-9 of the poses' norm, each solve 0.15 s); 0 leaves
  // the ending to Ceres.
  double last_step_gain = 1e-6;
  // Solve by our own Levenberg-Marquardt on the normal equations in the
  // poses' tangent, each window-shape factor adding its blocks directly and
  // CHOLMOD factoring them (src/graph/tangent_solver.cpp), where no robust
  // loss is set and the gauge holds whole poses; else, or when false, Ceres.
  bool normal_equations = true;
  // Not used by the solve, which runs on one thread so that its poses are
  // repeatable (src/graph/pose_graph.cpp); must be >= 0.
  int threads = 0;
  // Optional robust loss on each relative (window) factor's e^T Omega e;
  // `robust_loss_scale` is the whitened error norm (in "sigmas") where it
  // starts to down-weight.
  RobustLoss robust_loss = RobustLoss::None;
  double robust_loss_scale = 1.0;
  // The same for loop-closure factors, set apart because a wrong place match
  // is far likelier than a wrong window.
  RobustLoss loop_robust_loss = RobustLoss::None;
  double loop_robust_loss_scale = 1.0;
  // And for pose and position priors (GNSS has stretches of multipath).
  RobustLoss prior_robust_loss = RobustLoss::None;
  double prior_robust_loss_scale = 1.0;
  // Gauge, per connected component of the relative and loop factors: none of
  // its nodes is held when its priors fix all six degrees of freedom (a
  // positive definite pose prior, or positive definite position priors whose
  // positions lie at least `min_prior_spread` metres (root-sum-square) off
  // their best-fitting line). With weaker position priors only the
  // orientation of its smallest node is held; without priors, the whole
  // smallest node (node 0 for a connected sequence). Nodes that no factor
  // touches are returned unchanged.
  double min_prior_spread = 1.0;
};

struct PoseGraphResult {
  std::vector<Pose> poses;
  double initial_cost = 0.0;  // sum over factors of rho(e^T Omega e)
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;
  // The gauge the solve used: nodes held entirely, and nodes whose
  // orientation alone was held (ascending).
  std::vector<std::size_t> held_nodes;
  std::vector<std::size_t> orientation_held_nodes;
};

// Throws hba::Error if a factor names a node outside [0, initial.size()),
// links a node to itself, or has a non-finite measurement or a non-finite or
// indefinite information, or if a pose or a setting is invalid; the message
// names the factor's index and kind. Deterministic for a given input and
// settings.
PoseGraphResult optimizeFactorGraph(const std::vector<Pose>& initial, const FactorGraph& factors,
                                    const PoseGraphSettings& settings = {});

// The pyramid's graph of relative factors only: optimizeFactorGraph of
// FactorGraph(factors).
PoseGraphResult optimizePoseGraph(const std::vector<Pose>& initial,
                                  const std::vector<RelativePoseFactor>& factors,
                                  const PoseGraphSettings& settings = {});

// Sum over factors of e^T Omega e at `poses` (no robust loss).
double factorGraphCost(const std::vector<Pose>& poses, const FactorGraph& factors);
double poseGraphCost(const std::vector<Pose>& poses, const std::vector<RelativePoseFactor>& factors);

}  // namespace hba::graph

namespace hba {
template <>
struct EnumNames<graph::RobustLoss> {
  static constexpr const char* what = "robust loss";
  static constexpr EnumName<graph::RobustLoss> names[] = {{graph::RobustLoss::None, "none"},
                                                          {graph::RobustLoss::Huber, "huber"},
                                                          {graph::RobustLoss::Cauchy, "cauchy"}};
};
}  // namespace hba
