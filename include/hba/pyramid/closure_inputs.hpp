#pragma once
// What a caller may give the method beyond scans and poses (docs/closure.md):
// loop-closure pairs to verify and close, and position priors that set the
// map's frame. Both index the layer-1 frames.
#include <vector>

#include "hba/closure/loop_check.hpp"
#include "hba/graph/factors.hpp"

namespace hba::pyramid {

struct ClosureInputs {
  std::vector<closure::LoopPair> loops;            // e.g. from io::readLoopFile
  std::vector<graph::PositionPriorFactor> priors;  // e.g. from closure::attachPriors

  bool empty() const { return loops.empty() && priors.empty(); }
};

}  // namespace hba::pyramid
