#pragma once
// Levenberg-Marquardt on the pose graph's normal equations in the poses'
// tangent (NormalEquations), for graphs without robust losses whose gauge
// holds whole poses: the same minimum as the Ceres solve, without forming
// J^T J from the window-shape factors' dense rows.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/graph/factor_graph.hpp"
#include "hba/graph/pose_graph.hpp"

namespace hba::graph {

struct TangentSolve {
  std::vector<Pose> poses;
  double initial_cost = 0.0;  // sum of e^T Omega e
  double final_cost = 0.0;
  int iterations = 0;  // steps tried, each a factorization or a solve with the last factor
  bool converged = false;
};

// Moves the nodes with `variable[node]` (the others stay as given), until a
// taken step gains less than settings.last_step_gain or
// settings.function_tolerance of the cost, a step is below 1e-8 of the
// poses' norm, or settings.max_iterations steps. A step after a taken one
// first reuses the last factorization (a chord step), and such steps end
// the solve at a hundredth of those shares (they converge linearly).
TangentSolve solveInTangent(const std::vector<Pose>& initial, const FactorGraph& factors,
                            const std::vector<bool>& variable, const PoseGraphSettings& settings);

}  // namespace hba::graph
