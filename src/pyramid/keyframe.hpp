#pragma once
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::pyramid {

// Merges the plane points of a window's frames into one cloud expressed in
// the window's first frame (with the optimized poses), downsampled to
// `voxel`. Points that were not on a plane feature are left out: they would
// not form planes in upper layers either (the paper's observation).
PointCloud buildKeyframe(const std::vector<const PointCloud*>& clouds, const std::vector<Pose>& optimized,
                         const std::vector<std::vector<std::uint32_t>>& plane_point_indices, double voxel);

}  // namespace hba::pyramid
