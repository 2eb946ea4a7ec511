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
};

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

}  // namespace hba::graph

namespace hba {
template <>
struct EnumNames<graph::FactorPairs> {
  static constexpr const char* what = "factor pairs";
  static constexpr EnumName<graph::FactorPairs> names[] = {{graph::FactorPairs::Adjacent, "adjacent"},
                                                           {graph::FactorPairs::AllPairs, "all"},
                                                           {graph::FactorPairs::FromFirst, "from_first"}};
};
}  // namespace hba
