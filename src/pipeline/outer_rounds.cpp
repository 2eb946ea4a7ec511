#include "outer_rounds.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace hba::pipeline {

bool OuterRounds::stopAfter(int round, const PoseChange& move) {
  // The move in units of the tolerances: below 1, nothing moved that matters.
  const double size = std::max(move.translation_m / settings_.settle_translation_m,
                               move.rotation_deg / settings_.settle_rotation_deg);
  const std::string rounds = fmt::format("{} round{}", round, round == 1 ? "" : "s");
  const std::string moved =
      fmt::format("largest move {:.4f} m, {:.4f} deg", move.translation_m, move.rotation_deg);
  const double before = previous_;
  previous_ = size;
  if (size < 1.0) {
    why_ = RoundsStop::Settled;
    reason_ = fmt::format("settled after {}: {} (within {} m, {} deg)", rounds, moved,
                          settings_.settle_translation_m, settings_.settle_rotation_deg);
    return true;
  }
  if (round > 1 && size >= before) {
    why_ = RoundsStop::Stalled;
    reason_ =
        fmt::format("stopped after {}: {}, no less than the round before (the noise floor)", rounds, moved);
    return true;
  }
  if (round >= settings_.outer_iterations) {
    why_ = RoundsStop::Limit;
    reason_ = fmt::format("reached --iterations {}: {}", settings_.outer_iterations, moved);
    return true;
  }
  return false;
}

const char* toString(RoundsStop stop) {
  switch (stop) {
    case RoundsStop::Settled:
      return "poses settled";
    case RoundsStop::Stalled:
      return "moves stopped shrinking";
    case RoundsStop::Limit:
      break;
  }
  return "iteration limit";
}

}  // namespace hba::pipeline
