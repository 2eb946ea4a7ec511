#pragma once
// How much of what one local map shows as planes the other map shares.
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::closure {

// Share of the points of `map`'s own plane features (the map alone, at
// `planes`) that are among `shared_points` (sorted indices into `map`, the
// points on planes it shares with the other map). 0 when it has no planes.
double planeOverlap(const PointCloud& map, const std::vector<std::uint32_t>& shared_points,
                    const voxel::PlaneSettings& planes);

}  // namespace hba::closure
