#include "hba/ba/global_refinement.hpp"

#include "core/progress.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>

#include "core/stopwatch.hpp"
#include "hba/ba/association.hpp"
#include "hba/core/error.hpp"

namespace hba::ba {

namespace {

// A problem's size, of every member's planes when spread.
struct PlaneTotals {
  double planes = 0.0;
  double observations = 0.0;
  double points = 0.0;
};

PlaneTotals planeTotals(const PlaneProblem& problem) {
  PlaneTotals totals;
  totals.planes = static_cast<double>(problem.numPlanes());
  for (const PlaneObservation& plane : problem.planes()) {
    totals.observations += static_cast<double>(plane.clusters.size());
    totals.points += plane.pointCount();
  }
  if (problem.spread().spread()) {  // every member's planes (whole numbers: exact)
    totals.planes = static_cast<double>(problem.spread().allPlanes());
    const std::vector<std::vector<double>> all =
        gatherPerMember(*problem.spread().group, {totals.observations, totals.points});
    totals.observations = totals.points = 0.0;
    for (const std::vector<double>& theirs : all) {
      totals.observations += theirs.at(0);
      totals.points += theirs.at(1);
    }
  }
  return totals;
}

// Associations, each followed by an LM, from `initial` until a round gains
// little; the first round's figures go to `result`, the time and
// iterations add up over calls. A round that gains no more than fitting
// the noise would is not taken, and ends them (`converged`).
// `at_initial`: the first round's association, when made already (moved
// from, then null).
void solveRounds(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
                 const RefinementSettings& settings, const MotionPrior& prior,
                 const PositionPriors& positions, Association*& at_initial, RefinementResult& result) {
  result.poses = initial;
  result.converged = result.converged_at_start = false;
  // At most this many rounds: the ETA is an upper bound.
  Progress progress("refinement", static_cast<std::size_t>(settings.association_rounds), "rounds");
  for (int round = 0; round < settings.association_rounds; ++round, progress.advance()) {
    const auto start = Clock::now();
    Association association = round == 0 && at_initial != nullptr
                                  ? std::move(*at_initial)
                                  : refinementAssociation(scans, result.poses, settings);
    at_initial = nullptr;
    const auto associated = Clock::now();
    const PlaneProblem& problem = association.problem;
    const std::vector<Pose> before = result.poses;
    const PlaneTotals totals = planeTotals(problem);
    SparseLmSettings lm = settings.lm;
    lm.min_step_gain = settings.step_gain *
                       noiseFittingGain(association.cost(), totals.points, totals.planes, initial.size());
    const LmSummary summary =
        solveSparseLevenbergMarquardt(problem, result.poses, lm, prior, positions, association.cost());
    result.seconds_associate += secondsBetween(start, associated);
    result.seconds_solve += secondsBetween(associated, Clock::now());
    result.iterations += summary.iterations;
    result.cg_products += summary.cg_products;
    result.rounds = round + 1;
    const double plane_cost_after = problem.cost(result.poses);
    // The LM's objective (planes, motion prior, position priors) is what
    // a round must lower: with priors a round may pay in plane cost to
    // reach them.
    const double gain = summary.initial_cost - summary.final_cost;
    const double noise = noiseFittingGain(plane_cost_after, totals.points, totals.planes, initial.size());
    result.last_gain_over_noise = noise > 0.0 ? gain / noise : 0.0;
    const bool significant = summary.accepted_steps > 0 && gain > settings.significant_gain * noise;
    if (!significant) {
      result.poses = before;
      result.converged = true;
      result.converged_at_start = round == 0;
    }
    if (round == 0) {
      result.planes = static_cast<std::size_t>(totals.planes);
      result.observations = static_cast<std::size_t>(totals.observations);
      result.plane_points = static_cast<std::size_t>(totals.points);
      result.cost_before = association.cost();  // found at `before`
      result.cost_after = significant ? plane_cost_after : result.cost_before;
    }
    if (!significant) break;
    // A round that barely moved the cost has converged the association.
    if (summary.initial_cost - summary.final_cost < settings.round_gain * summary.initial_cost) break;
  }
}

// The pairs in `slid` and `reach` pairs either side, ascending, unique.
std::vector<std::size_t> widen(const std::vector<std::size_t>& slid, std::size_t reach, std::size_t pairs) {
  std::vector<std::size_t> out;
  for (const std::size_t k : slid) {
    for (std::size_t j = k >= reach ? k - reach : 0; j <= std::min(pairs - 1, k + reach); ++j) {
      out.push_back(j);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

double noiseFittingGain(double plane_cost, double points, double planes, std::size_t frames) {
  const double residual_points = points - 3.0 * planes;
  if (!(residual_points > 0.0) || frames < 2) return 0.0;
  return plane_cost / residual_points * 6.0 * static_cast<double>(frames - 1);
}

Association refinementAssociation(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                                  const RefinementSettings& settings) {
  if (settings.spread_over != nullptr && settings.spread_over->size() > 1)
    return associateSpread(scans, poses, settings.planes, settings.reject_ratio, *settings.spread_over);
  Association association = associate(scans, poses, settings.planes, settings.reject_ratio);
  // The points of each plane are summed into its clusters: their indices
  // (8 bytes a plane point) are not needed by the LM.
  association.extraction = {};
  return association;
}

RefinementResult refineGlobally(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
                                const RefinementSettings& settings, const std::vector<double>& path_m,
                                const std::vector<Pose>& reference, const PositionPriors& positions,
                                Association* at_initial) {
  if (scans.size() != initial.size()) {
    throw Error("refinement: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(initial.size()) + " poses");
  }
  if (settings.association_rounds < 1) throw Error("refinement: association_rounds must be >= 1");
  if (!(settings.round_gain >= 0.0)) throw Error("refinement: round_gain must be >= 0");
  if (!(settings.significant_gain >= 0.0)) throw Error("refinement: significant_gain must be >= 0");
  RefinementResult result;
  if (!reference.empty() && reference.size() != initial.size()) {
    throw Error("refinement: " + std::to_string(reference.size()) + " reference poses for " +
                std::to_string(initial.size()) + " frames");
  }
  for (const PositionTerm& term : positions.terms()) {
    if (term.frame >= initial.size()) {
      throw Error("refinement: a position prior on frame " + std::to_string(term.frame) + " of " +
                  std::to_string(initial.size()));
    }
  }
  const std::vector<Pose>& anchor = reference.empty() ? initial : reference;
  MotionPrior prior = neighbourPrior(anchor, path_m, settings.motion_prior);
  std::vector<std::size_t> held;
  for (int attempt = 0;; ++attempt) {
    solveRounds(scans, initial, settings, prior, positions, at_initial, result);
    if (!settings.motion_prior.enabled || initial.size() < 2) break;
    const std::vector<std::size_t> slid =
        stepsBeyondThePrior(anchor, result.poses, path_m, settings.slide_prior, settings.slide_sigmas);
    if (slid.empty()) break;
    if (attempt == settings.max_holds) {
      result.still_sliding = slid.size();
      break;
    }
    // Hold the pairs that slid, and their neighbours, near their start and
    // solve again: the planes still place everything else.
    const std::vector<std::size_t> hold = widen(slid, 2, initial.size() - 1);
    prior.tighten(hold, settings.hold_factor);  // again, for pairs that slid while held
    std::vector<std::size_t> all;
    std::set_union(held.begin(), held.end(), hold.begin(), hold.end(), std::back_inserter(all));
    held = std::move(all);
  }
  result.held_pairs = held.size();
  if (result.plane_points > 0) {
    const double n = static_cast<double>(result.plane_points);
    result.rms_before = std::sqrt(result.cost_before / n);
    result.rms_after = std::sqrt(result.cost_after / n);
  }
  return result;
}

}  // namespace hba::ba
