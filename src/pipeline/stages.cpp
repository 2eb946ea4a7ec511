// The stages around the paper's pyramid: the closures before it, the
// refinement and the priors' anchoring after it.
#include "stages.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "hba/closure/closure_graph.hpp"
#include "settings/refine_settings.hpp"
#include "shared_outcomes.hpp"

namespace hba::pipeline {

void closeLoops(Run& run) {
  // The verifications spread over the processes; the first one's outcome
  // sent to the others.
  run.closed = runClosureStage(run.scans.source(), run.input, run.closures, run.settings, run.group);
  if (run.group.size() > 1) shareClosures(run.group, run.closed);
  run.report.closure = run.closed.report;
  // Priors may put the start far from the input (UTM coordinates): the
  // stages after work near the start's first pose instead.
  run.shift = run.closed.start.front().t;
  run.closed.start = translated(run.closed.start, -run.shift);
  for (auto& prior : run.closed.priors) prior.position -= run.shift;
  run.input = translated(run.input, -run.shift);
  run.poses = run.closed.start;
}

void refineMap(Run& run) {
  HbaReport& report = run.report;
  refine::HierarchyFacts facts;
  facts.layers = run.layers;
  facts.layer_one_points = run.layer_one_points;
  facts.scans_kept = run.scans.kept();
  // Every process of a group runs it, each with its share of the planes
  // (docs/mpi.md).
  refine::RefineSettings settings = settings::refineSettingsOf(run.settings);
  settings.ba.spread_over = &run.group;
  // The motion prior and the self-check take the closed start as the
  // input: its steps are the input's, its loops closed.
  refine::RefineOutcome refined = refine::refineAndCheck(run.scans.source(), run.closed.start, run.poses,
                                                         facts, run.closed.priors, settings);
  run.poses = std::move(refined.poses);
  report.consistency = std::move(refined.consistency);
  const RefinementReport& r = refined.refinement;
  run.converged_at_start = r.converged_at_start;
  // Its blocks hold the priors themselves; the groups (which do not see
  // them) may move the frames after.
  run.priors_held = r.ran && !(r.groups.ran && !r.groups.rejected);
  report.refinement = std::move(refined.refinement);
  report.warnings.insert(report.warnings.end(), refined.notes.warnings.begin(), refined.notes.warnings.end());
  report.seconds_voxelize += refined.notes.seconds_voxelize;
  report.seconds_solve += refined.notes.seconds_solve;
}

void anchorOnPriors(Run& run) {
  const std::vector<graph::PositionPriorFactor>& priors = run.closed.priors;
  // The hierarchy (held at its first frame) does not hold the priors.
  if (priors.empty() || run.priors_held) return;
  closure::ClosureGraphSettings anchoring;
  anchoring.threads = run.settings.threads;
  const closure::ClosureGraphResult anchored =
      closure::anchorToPriors(run.poses, priors, anchoring, run.closures.session_starts);
  ClosureReport& c = run.report.closure;
  c.anchoring_move_m = largestChange(run.poses, anchored.poses).translation_m;
  c.anchoring_priors_dropped =
      static_cast<std::size_t>(std::count(anchored.prior_kept.begin(), anchored.prior_kept.end(), false));
  spdlog::info("re-anchored on {} priors: poses moved up to {:.3f} m",
               priors.size() - c.anchoring_priors_dropped, c.anchoring_move_m);
  run.poses = anchored.poses;
}

}  // namespace hba::pipeline
