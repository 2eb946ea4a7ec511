#pragma once
// Voxel-grid downsampling of a point cloud.
#include <cstddef>

#include "hba/core/point_cloud.hpp"

namespace hba::voxel {

// One point per occupied voxel of edge `voxel_size` (m); see the .cpp for the
// rule (centroid or first point). voxel_size <= 0 returns the input unchanged.
// `points_per_cell`: how many points a voxel is expected to gather, which
// sizes the voxel table (it grows if needed; the result never depends on
// it): about 1 for a scan at its own scan voxel, more for clouds merged from
// overlapping scans or taken to a coarser voxel. 0: 1, or 4 beyond 2^20
// points.
PointCloud downsample(const PointCloud& cloud, double voxel_size, std::size_t points_per_cell = 0);

}  // namespace hba::voxel
