#pragma once
// The refinement of a session against a map that stays put (`hba optimize
// NEW --map MAP`): one plane BA over the session's frames and the map as a
// frame of its own, held fixed, so the map's planes pull the session onto
// them and nothing moves the map. The session arrives placed in the map's
// frame and optimized on its own (within centimetres of the map).
#include <vector>

#include "hba/ba/global_refinement.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

// The map's points within `reach` (m) of any pose, in the map's point
// coordinates (map.origin kept): what the session can see of it.
PointCloud mapNear(const PointCloud& map, const std::vector<Pose>& poses, double reach);

// `poses`: the session's, in the map's point coordinates (relative to
// map.origin); `scans` the session's, downsampled. The result's poses are
// the session's alone (the map's frame is not returned: it does not move).
RefinementResult refineAgainstMap(const PointCloud& map, const std::vector<const PointCloud*>& scans,
                                  const std::vector<Pose>& poses, RefinementSettings settings);

}  // namespace hba::ba
