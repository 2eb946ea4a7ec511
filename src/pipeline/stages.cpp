// The stages around the paper's pyramid: the closures before it, the
// refinement and the priors' anchoring after it.
#include "stages.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "hba/closure/closure_graph.hpp"
#include "settings/refine_settings.hpp"
#include "shared_outcomes.hpp"

namespace hba::pipeline {

ClosedStart closeLoops(const RunInput& in) {
  ClosedStart out;
  // The verifications spread over the processes; the first one's outcome
  // sent to the others.
  out.closed = runClosureStage(in.scans.source(), in.input, in.closures, in.settings, in.group);
  if (in.group.size() > 1) shareClosures(in.group, out.closed);
  out.shift = out.closed.start.front().t;
  out.closed.start = translated(out.closed.start, -out.shift);
  for (auto& prior : out.closed.priors) prior.position -= out.shift;
  out.input = translated(in.input, -out.shift);
  return out;
}

namespace {

refine::HierarchyFacts factsOf(const RunInput& in, std::size_t layer_one_points) {
  refine::HierarchyFacts facts;
  facts.layers = in.layers;
  facts.layer_one_points = layer_one_points;
  facts.scans_kept = in.scans.kept();
  return facts;
}

// Every process of a group runs it, each with its share of the planes
// (docs/mpi.md).
refine::RefineSettings refiningOf(const RunInput& in) {
  refine::RefineSettings refining = settings::refineSettingsOf(in.settings);
  refining.ba.spread_over = &in.group;
  return refining;
}

}  // namespace

// The motion prior and the self-check take the closed start as the input:
// its steps are the input's, its loops closed.
refine::PreparedStart prepareRefinement(const RunInput& in, const ClosedStart& start,
                                        std::size_t layer_one_points) {
  return refine::prepareStart(in.scans.source(), start.closed.start, factsOf(in, layer_one_points),
                              refiningOf(in));
}

RefinedMap refineMap(const RunInput& in, const ClosedStart& start, const PyramidOutcome& pyramid,
                     refine::PreparedStart* prepared) {
  RefinedMap out;
  out.outcome = refine::refineAndCheck(in.scans.source(), start.closed.start, pyramid.poses,
                                       factsOf(in, pyramid.layer_one_points), start.closed.priors,
                                       refiningOf(in), prepared);
  const RefinementReport& r = out.outcome.refinement;
  // Its blocks hold the priors themselves; the groups (which do not see
  // them) may move the frames after.
  out.priors_held = r.ran && !(r.groups.ran && !r.groups.rejected);
  return out;
}

Anchoring anchorOnPriors(const RunInput& in, const ClosedStart& start, const RefinedMap& refined) {
  Anchoring out;
  const std::vector<graph::PositionPriorFactor>& priors = start.closed.priors;
  // The hierarchy (held at its first frame) does not hold the priors.
  if (priors.empty() || refined.priors_held) return out;
  closure::ClosureGraphSettings anchoring;
  anchoring.threads = in.settings.threads;
  const std::vector<Pose>& poses = refined.outcome.poses;
  const closure::ClosureGraphResult anchored =
      closure::anchorToPriors(poses, priors, anchoring, in.closures.session_starts);
  out.ran = true;
  out.move_m = largestChange(poses, anchored.poses).translation_m;
  out.priors_dropped =
      static_cast<std::size_t>(std::count(anchored.prior_kept.begin(), anchored.prior_kept.end(), false));
  spdlog::info("re-anchored on {} priors: poses moved up to {:.3f} m", priors.size() - out.priors_dropped,
               out.move_m);
  out.poses = anchored.poses;
  return out;
}

}  // namespace hba::pipeline
