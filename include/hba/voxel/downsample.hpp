#pragma once
// Voxel-grid downsampling of a point cloud.
#include "hba/core/point_cloud.hpp"

namespace hba::voxel {

// One point per occupied voxel of edge `voxel_size` (m); see the .cpp for the
// rule (centroid or first point). voxel_size <= 0 returns the input unchanged.
PointCloud downsample(const PointCloud& cloud, double voxel_size);

}  // namespace hba::voxel
