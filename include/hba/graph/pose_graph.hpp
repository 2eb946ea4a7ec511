#pragma once
// The top-down pose graph: all layer-1 poses as unknowns, relative-pose
// factors from the BA windows of every layer. Solved with Ceres
// (Levenberg-Marquardt, sparse normal Cholesky). See docs/graph.md.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

// A measured relative pose T_from^-1 * T_to with its 6x6 information matrix.
// The information is expressed in the tangent of the residual of
// hba/core/relative_pose_error.hpp (translation first, then rotation); it
// must be symmetric positive semi-definite.
struct RelativePoseFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};

enum class RobustLoss { None, Huber, Cauchy };

struct PoseGraphSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-10;
  int threads = 0;  // 0: all cores
  // Optional robust loss on each factor's e^T Omega e; `robust_loss_scale` is
  // the whitened error norm (in "sigmas") where it starts to down-weight.
  RobustLoss robust_loss = RobustLoss::None;
  double robust_loss_scale = 1.0;
  // Gauge: in every connected component of the factor graph the node with the
  // smallest index is held fixed (node 0 for a connected sequence). Nodes that
  // no factor touches are returned unchanged.
};

struct PoseGraphResult {
  std::vector<Pose> poses;
  double initial_cost = 0.0;  // sum over factors of rho(e^T Omega e)
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Throws hba::Error if a factor names a node outside [0, initial.size()),
// links a node to itself, or has a non-finite or indefinite information, or if
// a pose or a setting is invalid. Deterministic for a given input and settings.
PoseGraphResult optimizePoseGraph(const std::vector<Pose>& initial,
                                  const std::vector<RelativePoseFactor>& factors,
                                  const PoseGraphSettings& settings = {});

// Sum over factors of e^T Omega e at `poses` (no robust loss).
double poseGraphCost(const std::vector<Pose>& poses,
                     const std::vector<RelativePoseFactor>& factors);

}  // namespace hba::graph
