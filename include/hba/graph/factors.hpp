#pragma once
// The kinds of pose-graph factor, as plain data. A FactorGraph
// (hba/graph/factor_graph.hpp) takes any of them; optimizeFactorGraph
// (hba/graph/pose_graph.hpp) solves it. See docs/graph.md.
#include <cstddef>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

// A measured relative pose T_from^-1 * T_to with its 6x6 information matrix,
// from a BA window. The information is expressed in the tangent of the
// residual of hba/core/relative_pose_error.hpp (translation first, then
// rotation); it must be symmetric positive semi-definite.
struct RelativePoseFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};

// The same residual between two arbitrary nodes, from place recognition or
// from another session's map. Kept apart from the window factors so it can be
// counted and given its own robust loss (PoseGraphSettings::loop_robust_loss).
struct LoopClosureFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};

// A prior on one node's full pose in the world frame. Its residual is a
// relative factor's from the world origin, (R_m^T (t - t_m), Log(R_m^T R)),
// so the information is in the measurement's axes, translation first.
struct PosePriorFactor {
  std::size_t node = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};

// A prior on one node's position in the world frame (GNSS in a local metric
// frame, a surveyed point): residual t - position, information in world axes.
struct PositionPriorFactor {
  std::size_t node = 0;
  Vec3 position = Vec3::Zero();
  Mat3 information = Mat3::Identity();
};

// Which of the above a factor is, for counting and reports.
enum class FactorKind { Relative, LoopClosure, PosePrior, PositionPrior };

}  // namespace hba::graph
