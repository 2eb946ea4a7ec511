#include "hba/ba/global_refinement.hpp"

#include <cmath>
#include <string>

#include "hba/ba/association.hpp"
#include "hba/core/error.hpp"
#include "hba/core/stopwatch.hpp"

namespace hba::ba {

RefinementResult refineGlobally(const std::vector<const PointCloud*>& scans,
                                const std::vector<Pose>& initial,
                                const RefinementSettings& settings,
                                const std::vector<double>& path_m) {
  if (scans.size() != initial.size()) {
    throw Error("refinement: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(initial.size()) + " poses");
  }
  if (settings.association_rounds < 1) throw Error("refinement: association_rounds must be >= 1");
  if (!(settings.round_gain >= 0.0)) throw Error("refinement: round_gain must be >= 0");
  RefinementResult result;
  result.poses = initial;
  const MotionPrior prior = neighbourPrior(initial, path_m, settings.motion_prior);
  for (int round = 0; round < settings.association_rounds; ++round) {
    const auto start = Clock::now();
    const Association association =
        associate(scans, result.poses, settings.planes, settings.reject_ratio);
    const auto associated = Clock::now();
    const PlaneProblem& problem = association.problem;
    const std::vector<Pose> before = result.poses;
    const LmSummary summary = solveSparseLevenbergMarquardt(problem, result.poses, settings.lm, prior);
    result.seconds_associate += secondsBetween(start, associated);
    result.seconds_solve += secondsBetween(associated, Clock::now());
    result.iterations += summary.iterations;
    result.rounds = round + 1;
    if (round == 0) {
      result.planes = problem.numPlanes();
      for (const PlaneObservation& plane : problem.planes()) {
        result.observations += plane.clusters.size();
        result.plane_points += static_cast<std::size_t>(plane.pointCount());
      }
      result.cost_before = problem.cost(before);
      result.cost_after = problem.cost(result.poses);
    }
    if (summary.accepted_steps == 0) break;
    // A round that barely moved the cost has converged the association.
    if (summary.initial_cost - summary.final_cost < settings.round_gain * summary.initial_cost) break;
  }
  if (result.plane_points > 0) {
    const double n = static_cast<double>(result.plane_points);
    result.rms_before = std::sqrt(result.cost_before / n);
    result.rms_after = std::sqrt(result.cost_after / n);
  }
  return result;
}

}  // namespace hba::ba
