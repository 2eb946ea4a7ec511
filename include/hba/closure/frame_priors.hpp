#pragma once
// Position priors (timed, from a file) attached to the frames of a sequence.
// A prior rarely falls on a scan's stamp: it goes to the frame nearest in
// time, moved by the odometry's own motion between the two instants (the
// odometry is precise over fractions of a second, the prior is not).
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/graph/factors.hpp"
#include "hba/io/position_prior_file.hpp"

namespace hba::closure {

struct FramePriors {
  std::vector<graph::PositionPriorFactor> factors;  // information = diag(1 / sigma^2)
  std::vector<std::size_t> lines;                   // the file line of each factor
  std::size_t outside = 0;  // priors with no frame within `max_gap_s` (before, after or in a gap)
};

// `odometry` needs stamps (increasing). Throws hba::Error when it has none.
FramePriors attachPriors(const std::vector<io::TimedPosition>& priors, const Trajectory& odometry,
                         double max_gap_s);

}  // namespace hba::closure
