#pragma once
// The last stage of hba optimize: the self-check on the input's planes and
// the sparse plane BA over every layer-1 frame (docs/pyramid.md,
// "Refinement and self-check").
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/settings.hpp"

namespace hba::pyramid {

// Returns the final poses from the input poses and the hierarchy's (built
// with report.layers layers); fills report.consistency and
// report.refinement and adds warnings.
std::vector<Pose> refineAndCheck(const io::ScanSource& scans, const std::vector<Pose>& initial,
                                 const std::vector<Pose>& hierarchy, const HbaSettings& settings,
                                 HbaReport& report);

}  // namespace hba::pyramid
