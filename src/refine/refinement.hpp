#pragma once
// The last stage of hba optimize: the self-check on the input's planes and
// the sparse plane BA over every layer-1 frame (docs/pyramid.md,
// "Refinement and self-check").
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/graph/factors.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/settings.hpp"

namespace hba::pyramid {

// Returns the final poses from the input poses and the hierarchy's (built
// with report.layers layers); fills report.consistency and
// report.refinement and adds warnings. `priors` (the closure stage's kept
// ones, in the poses' coordinates) hold the refinement's long-range shape.
// `scans_kept`: `scans` reads each scan once and keeps it (TimedClouds with
// keep), so the blocks and groups need no copy of their own.
std::vector<Pose> refineAndCheck(const io::ScanSource& scans, const std::vector<Pose>& initial,
                                 const std::vector<Pose>& hierarchy, const HbaSettings& settings,
                                 HbaReport& report,
                                 const std::vector<graph::PositionPriorFactor>& priors = {},
                                 bool scans_kept = false);

}  // namespace hba::pyramid
