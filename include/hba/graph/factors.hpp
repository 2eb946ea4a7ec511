#pragma once
// The kinds of pose-graph factor, as plain data. A FactorGraph
// (hba/graph/factor_graph.hpp) takes any of them; optimizeFactorGraph
// (hba/graph/pose_graph.hpp) solves it. See docs/graph.md.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

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

// The shape of one whole BA window: the relative pose of each of its frames
// k = 1 .. K-1 from its first, T_0^-1 T_k, measured together, with one
// joint information matrix over the stacked residuals (those of
// hba/core/relative_pose_error.hpp, frame 1's first). Unlike K-1 separate
// factors, it keeps how the window's frames move together: the second-order
// model of the window's own cost, each point counted once.
struct WindowShapeFactor {
  std::vector<std::size_t> nodes;  // K >= 2 distinct nodes, the first is the window's gauge
  std::vector<Pose> relative;      // K-1 measurements, relative[k-1] for frame k
  Eigen::MatrixXd information;     // 6(K-1) x 6(K-1), symmetric positive semi-definite
};

// Which of the above a factor is, for counting and reports.
enum class FactorKind { Relative, LoopClosure, PosePrior, PositionPrior, WindowShape };

}  // namespace hba::graph
