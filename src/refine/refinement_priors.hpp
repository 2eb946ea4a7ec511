#pragma once
// The closure stage's kept position priors, as terms of the refinement's
// plane BA over a block of consecutive frames.
#include <cstddef>
#include <vector>

#include "hba/ba/position_prior.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/factors.hpp"

namespace hba::refine {

// Priors whose frames are at least this spread (m, one sigma, along two
// directions) fix the frame: no pose is held as the gauge then.
inline constexpr double kPriorSpreadForGauge = 10.0;

// The priors on frames [first, end), indexed from `first`; the information
// scaled into plane-cost units (`point_sigma`, the motion prior's).
ba::PositionPriors blockPriors(const std::vector<graph::PositionPriorFactor>& priors, std::size_t first,
                               std::size_t end, double point_sigma);

}  // namespace hba::refine
