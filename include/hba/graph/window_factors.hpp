#pragma once
// Turns one optimized BA window into pose-graph factors (the top-down step of
// the pyramid): measurements are the window's optimized relative poses,
// information comes from the window's Hessian (hba/graph/information.hpp).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/information.hpp"
#include "hba/graph/pose_graph.hpp"

namespace hba::graph {

// Which frame pairs of a window of K frames get a factor.
enum class FactorPairs {
  Adjacent,   // (k, k+1): K-1 factors, the paper's choice
  AllPairs,   // every (i, j) with i < j: K(K-1)/2 factors
  FromFirst,  // (0, k): K-1 factors, the BA's own gauge frame to every frame
  Joint,      // none: one WindowShapeFactor (windowShapeFactor below) instead
};

// Windows of more frames than this get adjacent factors under
// FactorPairs::Joint instead: the joint factor's information is dense, of
// (6(K-1))^2 numbers, and so is the pose graph's system over its frames.
inline constexpr std::size_t kMaxJointFrames = 128;

// `hessian` (6K x 6K) and `optimized_window_poses` (K) come from one BA window
// (hba::ba::BaResult); `nodes[k]` is the pose-graph node of window frame k
// (the layer-1 scan a keyframe's window starts at). Each factor's measurement is
// relative(poses[i], poses[j]) for a window pair (i, j), mapped to nodes
// (nodes[i], nodes[j]). All pairs share one inversion of
// the window's Hessian. Throws hba::Error when the sizes disagree, two
// frames map to the same node, or the Hessian is invalid.
std::vector<RelativePoseFactor> windowFactors(const Eigen::MatrixXd& hessian,
                                              const std::vector<Pose>& optimized_window_poses,
                                              const std::vector<std::size_t>& nodes, FactorPairs pairs,
                                              const InformationSettings& settings = {});

// The whole window as one factor (FactorPairs::Joint): the relative pose of
// every frame from the first, and as information the inverse of their joint
// covariance with the first frame held (the gauge-fixed Fisher information
// of the window, mapped into the residuals' tangent). Its cost is then the
// window's own second-order cost model: K-1 separate factors would drop how
// the frames' errors go together, and all pairs would count each point K-1
// times. Same inputs and errors as windowFactors.
WindowShapeFactor windowShapeFactor(const Eigen::MatrixXd& hessian,
                                    const std::vector<Pose>& optimized_window_poses,
                                    const std::vector<std::size_t>& nodes,
                                    const InformationSettings& settings = {});

}  // namespace hba::graph

namespace hba {
template <>
struct EnumNames<graph::FactorPairs> {
  static constexpr const char* what = "factor pairs";
  static constexpr EnumName<graph::FactorPairs> names[] = {{graph::FactorPairs::Adjacent, "adjacent"},
                                                           {graph::FactorPairs::AllPairs, "all"},
                                                           {graph::FactorPairs::FromFirst, "from_first"},
                                                           {graph::FactorPairs::Joint, "joint"}};
};
}  // namespace hba
