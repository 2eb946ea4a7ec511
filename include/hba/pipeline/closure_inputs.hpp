#pragma once
// What a caller may give the method beyond scans and poses (docs/closure.md):
// loop-closure pairs to verify and close, and position priors that set the
// map's frame. Both index the layer-1 frames.
#include <vector>

#include "hba/closure/loop_check.hpp"
#include "hba/graph/factors.hpp"

namespace hba::pipeline {

struct ClosureInputs {
  std::vector<closure::LoopPair> loops;            // e.g. from io::readLoopFile
  std::vector<graph::PositionPriorFactor> priors;  // e.g. from closure::attachPriors
  // Several sessions as one sequence: the frames where each later session
  // starts (closure/sessions.hpp). Their input poses must already be in one
  // frame, roughly (an initial alignment); revisits between sessions are
  // then always searched, and no odometry step links a session to the one
  // before.
  std::vector<std::size_t> session_starts;

  bool empty() const { return loops.empty() && priors.empty() && session_starts.empty(); }
};

}  // namespace hba::pipeline
