#pragma once
// Levenberg-Marquardt for plane BA over many frames (thousands): the
// Hessian is never formed. Each plane keeps its factored linearization
// (Z^T diag(w) Z plus per-frame blocks, see plane_cost.hpp), so a product
// H x costs O(sum over planes of the frames that see them), and the damped
// system is solved by conjugate gradients with a block-Jacobi
// preconditioner (ba/factored_system.hpp holds the system). Memory and
// time per iteration grow with the number of observations, not with the
// square or cube of the frame count. Frame 0 is held fixed (gauge) unless
// position priors define the frame. Deterministic for any thread count.
#include <cstddef>
#include <optional>
#include <vector>

#include "hba/ba/lm_solver.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/ba/position_prior.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

struct SparseLmSettings {
  int max_iterations = 10;                // LM steps (accepted or not)
  double relative_cost_tolerance = 1e-5;  // stop when a step gains less than this share
  double initial_damping = 1e-4;          // mu, relative to the Hessian diagonal
  // Stop also when a step gains less than this (cost, m^2; 0: off): the
  // caller's measure of a gain too small to matter (the refinement: a share
  // of what fitting the points' noise gains).
  double min_step_gain = 0.0;
  // Inexact steps: the hierarchy has already removed the long-range error,
  // so loose steps suffice (docs/ba.md: tighter ones gave the same maps, in
  // more time). The cap also keeps the steps off bends hundreds of frames
  // long, along which the plane cost is nearly flat and leans the wrong way:
  // a solver that reached them (a two-level preconditioner) bent nclt by
  // 3.5 m (docs/ba.md). Raise it only with a prior on the long-range shape.
  int cg_max_iterations = 50;           // per LM step
  double cg_relative_tolerance = 1e-2;  // residual norm, relative to the first
  // A step that moves any frame further than this is scaled down to it:
  // the refinement polishes centimetres, and a frame that the planes leave
  // (nearly) free must not be thrown away along the free direction.
  double max_step_m = 0.5;
  double max_step_deg = 5.0;
  // Up to this many frames the damped system is formed and factored
  // instead (exact steps, (6K)^2 memory): for few unknowns whose weak,
  // long-range modes conjugate gradients reach only slowly (the rigid
  // groups of a long sequence). 0: always conjugate gradients.
  std::size_t dense_max_frames = 0;
  // Frame 0 held as the gauge. Off only where position priors fix the
  // frame (PositionPriors::defineTheFrame): the plane cost does not.
  bool hold_first = true;
};

// The preconditioner's inverse of one frame's damped 6x6 block: the exact
// inverse where the block is positive definite and well conditioned (its
// smallest LDLT pivot above 1e-9 of the largest); otherwise the inverse of
// its absolute eigenvalues, floored at 1e-9 of the largest. Always
// positive definite and finite.
Mat6 positiveInverse(const Mat6& block);

// Optimizes `poses` in place on the plane cost plus `prior` plus `positions`.
// `start_plane_cost`: problem.cost(poses), when the caller has it already.
LmSummary solveSparseLevenbergMarquardt(const PlaneProblem& problem, std::vector<Pose>& poses,
                                        const SparseLmSettings& settings, const MotionPrior& prior = {},
                                        const PositionPriors& positions = {},
                                        std::optional<double> start_plane_cost = std::nullopt);

}  // namespace hba::ba
