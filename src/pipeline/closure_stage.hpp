#pragma once
// The closure stage (docs/closure.md): loops from the caller and revisits
// found by the poses are verified with the plane BA; the verified loops and
// the position priors, with the input's own steps, make a pose graph whose
// solution is where the hierarchy starts. The loops and priors that survive
// stay in the hierarchy's pose graph.
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"
#include "hba/graph/factors.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"

namespace hba::pipeline {

struct ClosureOutcome {
  std::vector<Pose> start;  // the hierarchy's start: the input with loops closed and priors met
  std::vector<graph::LoopClosureFactor> loops;     // verified and kept
  std::vector<graph::PositionPriorFactor> priors;  // kept
  ClosureReport report;
};

// `clouds` as the layer-1 windows load them; `initial` the input poses (and
// `closures` its frames' loops and priors, in the same coordinates).
// Every member of `group` calls it (a collective): the candidates'
// verifications are spread over the members; the pose graph that closes
// them runs in the first, whose outcome is the only whole one (the others
// get it from shareClosures).
ClosureOutcome runClosureStage(const io::ScanSource& clouds, const std::vector<Pose>& initial,
                               const ClosureInputs& closures, const HbaSettings& settings,
                               const dist::Group& group = dist::singleProcess());

}  // namespace hba::pipeline
