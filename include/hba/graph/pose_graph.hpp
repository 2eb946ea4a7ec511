#pragma once
// The top-down pose graph: all layer-1 poses as unknowns, relative-pose
// factors from the BA windows of every layer. Solved with Ceres.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

// A measured relative pose T_from^-1 * T_to with its 6x6 information matrix.
// The information is expressed in the tangent of the residual documented in
// pose_graph.cpp (translation first, then rotation).
struct RelativePoseFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 information = Mat6::Identity();
};

struct PoseGraphSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-10;
  int threads = 0;  // 0: all cores
  // The first pose is held fixed (gauge); with `prior_on_all` the initial
  // poses also pull weakly on every node so that unconstrained nodes stay put.
};

struct PoseGraphResult {
  std::vector<Pose> poses;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Throws hba::Error if a factor names a node outside [0, initial.size()).
PoseGraphResult optimizePoseGraph(const std::vector<Pose>& initial,
                                  const std::vector<RelativePoseFactor>& factors,
                                  const PoseGraphSettings& settings = {});

}  // namespace hba::graph
