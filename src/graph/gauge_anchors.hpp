#pragma once
// Which nodes hold the gauge: a pose graph is invariant to one rigid motion
// per connected component, so one node per component must stay fixed.
#include <cstddef>
#include <vector>

#include "hba/graph/pose_graph.hpp"

namespace hba::graph {

// The smallest node index of every connected component that has a factor,
// ascending. Factor indices must already be valid.
std::vector<std::size_t> gaugeAnchors(std::size_t num_nodes,
                                      const std::vector<RelativePoseFactor>& factors);

}  // namespace hba::graph
