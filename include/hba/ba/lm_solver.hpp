#pragma once
// Levenberg-Marquardt on the poses of a PlaneProblem, frame 0 held fixed
// (the cost is invariant to one rigid motion of all frames). Dense Cholesky
// (LLT) on the 6(K-1) system; an accepted step always lowers the cost.
#include <optional>
#include <vector>

#include "hba/ba/motion_prior.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

struct LmSettings {
  int max_iterations = 10;                // linear solves (accepted or not)
  double relative_cost_tolerance = 1e-6;  // stop when a step gains less than this
  double initial_damping = 1e-4;          // mu, relative to the Hessian diagonal
};

struct LmSummary {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  int accepted_steps = 0;
  int cg_products = 0;  // products H x of the conjugate gradients (sparse solver)
  // The solver linearizes only where it steps from; the caller linearizes
  // at the poses it finally keeps (or takes the solver's: `settled` below).
};

// Applies the update of window_ba.hpp: R <- Exp(dphi) R, t <- t + dt, with
// delta holding (dt, dphi) of each frame in order.
std::vector<Pose> applyUpdate(const std::vector<Pose>& poses, const Eigen::VectorXd& delta);

// Optimizes `poses` in place, on the plane cost plus `prior` (may be empty).
// `start_plane_cost`: problem.cost(poses), when the caller has it already
// (Association::cost() of an association found at `poses`). `settled`:
// where given, the linearization (prior added) the solver last stepped
// from, when the solve settled: at the returned poses (its last step was
// declined), or one step before them when that step gained at most
// relative_cost_tolerance of the cost (and ended the solve). Empty when the
// solve ended otherwise (the iteration cap after a larger step).
LmSummary solveLevenbergMarquardt(const PlaneProblem& problem, std::vector<Pose>& poses,
                                  const LmSettings& settings, const MotionPrior& prior = {},
                                  std::optional<double> start_plane_cost = std::nullopt,
                                  Linearization* settled = nullptr);

}  // namespace hba::ba
