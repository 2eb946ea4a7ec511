#include "hba/ba/window_ba.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

#include "core/stopwatch.hpp"
#include "hba/ba/association.hpp"
#include "hba/ba/lm_solver.hpp"
#include "hba/ba/offset_noise.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/core/error.hpp"

namespace hba::ba {
namespace {

void validate(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
              const BaSettings& settings) {
  if (scans.size() != initial.size()) {
    throw Error("window BA: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(initial.size()) + " poses");
  }
  for (const PointCloud* scan : scans) {
    if (scan == nullptr) throw Error("window BA: null scan");
  }
  if (settings.max_iterations < 0 || settings.association_rounds < 1 ||
      !(settings.reject_ratio >= 0.0 && settings.reject_ratio < 1.0) ||
      !(settings.relative_cost_tolerance >= 0.0) ||
      !(settings.planes.voxel_size > 0.0 && std::isfinite(settings.planes.voxel_size)) ||
      !(settings.final_voxel_size >= 0.0 && std::isfinite(settings.final_voxel_size)) ||
      !(settings.significant_gain >= 0.0 && std::isfinite(settings.significant_gain))) {
    throw Error(
        "window BA: invalid settings (need max_iterations >= 0, association_rounds >= 1, "
        "0 <= reject_ratio < 1, relative_cost_tolerance >= 0, voxel_size > 0, "
        "final_voxel_size >= 0, significant_gain >= 0)");
  }
}

// RMS point-to-plane distance of each plane, from its cost.
std::vector<double> planeRms(const PlaneProblem& problem, std::vector<double> costs) {
  for (std::size_t p = 0; p < costs.size(); ++p) {
    costs[p] = std::sqrt(costs[p] / problem.planes()[p].pointCount());
  }
  return costs;
}

// The trust and settle checks of `poses` on `planes`, the finest planes
// found at the input poses (`cost_at_input` there).
struct InputCheck {
  double cost_final = 0.0;  // of `planes` at `poses`
  bool trusted = false;
  bool settled = false;
  double gain_over_noise = 0.0;
};

// The settle check: `gain` no more than significant_gain times what fitting
// the frames to noise would (`noise`).
bool settles(double gain, double noise, const BaSettings& settings) {
  return settings.significant_gain > 0.0 && noise > 0.0 && gain <= settings.significant_gain * noise;
}

InputCheck checkAgainstInput(const PlaneProblem& planes, double cost_at_input,
                             const std::vector<Pose>& initial, const std::vector<Pose>& poses,
                             const std::vector<double>& path_m, const BaSettings& settings) {
  InputCheck check;
  check.cost_final = planes.cost(poses);
  // Not trusted: a blurrier map on the input's own planes, or neighbouring
  // frames pulled apart far beyond what the prior allows (planes that
  // merge unrelated surfaces can make a map look crisper while frames
  // slide by metres).
  const bool slid =
      settings.motion_prior.enabled && settings.slide_sigmas > 0.0 &&
      !stepsBeyondThePrior(initial, poses, path_m, settings.motion_prior, settings.slide_sigmas).empty();
  const double gain = cost_at_input - check.cost_final;
  check.trusted = !slid && gain >= 0.0;
  if (!check.trusted) return check;
  // Settled: no more gained than fitting the frames to noise would.
  const double noise = offsetNoiseGain(frameOffsets(planes, poses), initial.size());
  check.gain_over_noise = noise > 0.0 ? gain / noise : 0.0;
  check.settled = settles(gain, noise, settings);
  return check;
}

// What one Gauss-Newton step from `lin` would gain, frame 0 held (the
// window's gauge); infinite where the Hessian gives no such step.
double gaussNewtonGain(const Linearization& lin) {
  const Eigen::Index n = lin.gradient.size() - 6;
  if (n <= 0) return 0.0;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(lin.hessian.bottomRightCorner(n, n));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd g = lin.gradient.tail(n);
  const double gain = 0.5 * g.dot(ldlt.solve(g));
  return std::isfinite(gain) && gain >= 0.0 ? gain : std::numeric_limits<double>::infinity();
}

// The trust and settle checks of the window's result on `fixed`, its finest
// planes found at the input poses: sets result's `trusted`, `settled`,
// `gain_over_noise` and fixed-map costs. A result that fails (blurrier
// there, or frames slid apart) after coarser rounds is not yet the window's
// verdict: at a converged map a coarse round carries a window off an input
// its finest planes already hold, and the finest round, on planes found
// where it went, need not bring it back. Those planes are then solved once
// more from the input, and that result is judged instead (becoming `last`,
// its linearization `last_lin`) when it passes. Where a Gauss-Newton step
// from the input could gain no more than the settle check allows, the
// window settles without the solve, and `input_lin` holds that
// linearization (its Hessian there).
void judgeAgainstInput(const std::shared_ptr<const Association>& fixed, const std::vector<Pose>& initial,
                       const LmSettings& lm, const MotionPrior& prior, const std::vector<double>& path_m,
                       const BaSettings& settings, std::shared_ptr<const Association>& last,
                       Linearization& last_lin, Linearization& input_lin, BaResult& result) {
  InputCheck check =
      checkAgainstInput(fixed->problem, fixed->cost(), initial, result.poses, path_m, settings);
  if (!check.trusted && fixed != last) {
    result.solved_again_at_input = true;
    Linearization at_input = fixed->problem.linearize(initial);
    prior.addTo(at_input, initial);
    const double noise = offsetNoiseGain(frameOffsets(fixed->problem, initial), initial.size());
    const double predicted = gaussNewtonGain(at_input);
    if (settles(predicted, noise, settings)) {
      check = InputCheck{fixed->cost(), true, true, predicted / noise};
      input_lin = std::move(at_input);
    } else {
      std::vector<Pose> again = initial;
      Linearization again_lin;
      const auto start = Clock::now();
      const LmSummary summary =
          solveLevenbergMarquardt(fixed->problem, again, lm, prior, fixed->cost(), &again_lin);
      result.seconds_solve += secondsBetween(start, Clock::now());
      result.iterations += summary.iterations;
      const InputCheck again_check =
          checkAgainstInput(fixed->problem, fixed->cost(), initial, again, path_m, settings);
      if (again_check.trusted) {
        check = again_check;
        result.poses = std::move(again);
        last = fixed;
        last_lin = std::move(again_lin);
      }
    }
  }
  result.fixed_map_cost_initial = fixed->cost();
  result.fixed_map_cost_final = check.cost_final;
  result.trusted = check.trusted;
  result.settled = check.settled;
  result.gain_over_noise = check.gain_over_noise;
}

}  // namespace

BaResult optimizeWindow(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
                        const BaSettings& settings, const std::vector<double>& path_m) {
  validate(scans, initial, settings);
  const MotionPrior full_prior = neighbourPrior(initial, path_m, settings.motion_prior);
  const MotionPrior no_prior;
  BaResult result;
  result.poses = initial;
  const LmSettings lm{settings.max_iterations, settings.relative_cost_tolerance};

  // The last round's planes, and the trust check's: at the input poses and
  // the finest voxel, found with the first round's (the same points placed
  // once), or the first round's own when it is at the finest voxel already.
  std::shared_ptr<const Association> last, fixed;
  Linearization last_lin;      // where the last round's solver settled, when it did
  Linearization input_lin;     // at the input on the finest planes, when made for the trust check
  bool last_at_input = false;  // `last` was found at the input poses
  // Halvings from voxel_size down to final_voxel_size (coarse to fine).
  const double coarsest = settings.planes.voxel_size;
  const double finest =
      settings.final_voxel_size > 0.0 ? std::min(settings.final_voxel_size, coarsest) : coarsest;
  const int halvings = static_cast<int>(std::ceil(std::log2(coarsest / finest) - 1e-9));
  BaSettings round_settings = settings;
  for (int round = 0; round < settings.association_rounds + halvings; ++round) {
    round_settings.planes.voxel_size = std::max(finest, coarsest / std::pow(2.0, round));
    const bool at_finest = round >= halvings;
    const auto start = Clock::now();
    if (round == 0 && settings.check_fixed_map && halvings > 0) {
      auto [coarse, fine] =
          associateAtTwoVoxels(scans, result.poses, round_settings.planes, finest, settings.reject_ratio);
      last = std::make_shared<const Association>(std::move(coarse));
      fixed = std::make_shared<const Association>(std::move(fine));
      last_at_input = true;
    } else {
      last = std::make_shared<const Association>(
          associate(scans, result.poses, round_settings.planes, settings.reject_ratio));
      if (round == 0 && settings.check_fixed_map) fixed = last;
      last_at_input = round == 0;
    }
    // Without planes there is nothing to weigh the prior against.
    const MotionPrior& prior = last->problem.numPlanes() > 0 ? full_prior : no_prior;
    const auto associated = Clock::now();
    // The association found its planes at these poses: their cost is known.
    const LmSummary summary =
        solveLevenbergMarquardt(last->problem, result.poses, lm, prior, last->cost(), &last_lin);
    result.seconds_associate += secondsBetween(start, associated);
    result.seconds_solve += secondsBetween(associated, Clock::now());
    result.iterations += summary.iterations;
    result.rounds = round + 1;
    if (round == 0) result.initial_cost = summary.initial_cost;
    const double gain = summary.initial_cost - summary.final_cost;
    if (at_finest && !(gain > settings.relative_cost_tolerance * summary.initial_cost)) break;  // settled
  }

  if (settings.check_fixed_map) {
    judgeAgainstInput(fixed, initial, lm, fixed->problem.numPlanes() > 0 ? full_prior : no_prior, path_m,
                      settings, last, last_lin, input_lin, result);
    if (!result.trusted || result.settled) {
      result.poses = initial;
      last = fixed;
    }
    if (last == fixed) last_at_input = true;  // the finest planes found at the input
  }
  const bool moved = result.trusted && !result.settled;
  const MotionPrior& prior = last->problem.numPlanes() > 0 ? full_prior : no_prior;
  // Each plane's cost at the result and at the input, once for the totals
  // and the RMS figures (the association's own where it was found there).
  const std::vector<double> initial_costs =
      last_at_input ? last->plane_costs : last->problem.planeCosts(initial);
  // Not moved: the result is the input, and `last` the trust check's planes found there.
  const std::vector<double> final_costs = moved ? last->problem.planeCosts(result.poses) : initial_costs;
  result.final_cost = PlaneProblem::total(final_costs);
  // The Hessian where the last round's solver settled: at the result, or
  // one step before it that gained at most the tolerance (the step is
  // taken; its Hessian is not made again for so small a move).
  Linearization final_lin;
  if (moved && last_lin.gradient.size() > 0) {
    final_lin = std::move(last_lin);
  } else if (!moved && input_lin.gradient.size() > 0) {
    final_lin = std::move(input_lin);  // at the input, on the same planes
  } else {
    final_lin = last->problem.linearize(result.poses);
    prior.addTo(final_lin, result.poses);
  }
  result.hessian = std::move(final_lin.hessian);
  result.last_association_initial_cost = PlaneProblem::total(initial_costs);
  result.num_planes = last->problem.numPlanes();
  for (const PlaneObservation& plane : last->problem.planes()) {
    result.num_plane_points += static_cast<std::size_t>(plane.pointCount());
  }
  result.plane_rms_initial = planeRms(last->problem, initial_costs);
  result.plane_rms_final = planeRms(last->problem, final_costs);
  result.plane_point_indices = last->extraction.pointIndicesPerScan();
  return result;
}

}  // namespace hba::ba
