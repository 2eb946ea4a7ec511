#pragma once
// The kinds of pose-graph factor, as plain data, each with the function
// that makes its solver model (one source file a kind in src/graph). A
// FactorGraph (hba/graph/factor_graph.hpp) takes any of them;
// optimizeFactorGraph (hba/graph/pose_graph.hpp) solves it. A new kind is
// its struct and modelOf() here, its source file, and one CMake line. See
// docs/graph.md.
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

// The solver's view of one factor (src/graph/factor_model.hpp).
class FactorModel;
using FactorModelPtr = std::shared_ptr<const FactorModel>;

// Which robust loss of PoseGraphSettings a between factor gets.
enum class BetweenLoss { Window, Loop };

// A measured relative pose T_from^-1 * T_to with its 6x6 information matrix.
// The information is expressed in the tangent of the residual of
// hba/core/relative_pose_error.hpp (translation first, then rotation); it
// must be symmetric positive semi-definite. `Loss` tags the robust loss.
template <BetweenLoss Loss>
struct BetweenFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};
// From a BA window.
using RelativePoseFactor = BetweenFactor<BetweenLoss::Window>;
// Between two arbitrary nodes, from place recognition or from another
// session's map: counted apart, under its own robust loss
// (PoseGraphSettings::loop_robust_loss).
using LoopClosureFactor = BetweenFactor<BetweenLoss::Loop>;

FactorModelPtr betweenModel(std::size_t from, std::size_t to, const Pose& measurement,
                            const Mat6& information,
                            BetweenLoss loss);  // between_factor_model.cpp
template <BetweenLoss Loss>
FactorModelPtr modelOf(const BetweenFactor<Loss>& factor) {
  return betweenModel(factor.from, factor.to, factor.measurement, factor.information, Loss);
}

// A prior on one node's full pose in the world frame. Its residual is a
// relative factor's from the world origin, (R_m^T (t - t_m), Log(R_m^T R)),
// so the information is in the measurement's axes, translation first.
struct PosePriorFactor {
  std::size_t node = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};
FactorModelPtr modelOf(const PosePriorFactor& factor);  // pose_prior_factor.cpp

// A prior on one node's position in the world frame (GNSS in a local metric
// frame, a surveyed point): residual t - position, information in world axes.
struct PositionPriorFactor {
  std::size_t node = 0;
  Vec3 position = Vec3::Zero();
  Mat3 information = Mat3::Identity();
};
FactorModelPtr modelOf(const PositionPriorFactor& factor);  // position_prior_factor.cpp

// A prior on one node's height in the world frame (a barometer, a floor
// known to be level): residual z - height, information 1 / sigma^2 (1/m^2).
struct HeightPriorFactor {
  std::size_t node = 0;
  double height = 0.0;
  double information = 1.0;
};
FactorModelPtr modelOf(const HeightPriorFactor& factor);  // height_prior_factor.cpp

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
FactorModelPtr modelOf(const WindowShapeFactor& factor);  // window_shape_factor.cpp

}  // namespace hba::graph
