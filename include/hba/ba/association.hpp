#pragma once
// From voxel plane features to BA plane observations: per-frame point
// clusters in sensor coordinates, and the outlier filter on plane residuals.
#include <cstddef>
#include <vector>

#include "hba/ba/plane_cost.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::ba {

// One observation per feature, with one cluster per observing frame (sorted
// by frame). The only pass over the points: the LM loop never sees them.
std::vector<PlaneObservation> buildObservations(const std::vector<voxel::PlaneFeature>& features,
                                                const std::vector<const PointCloud*>& scans);

// Indices (ascending) of the planes kept when the worst `reject_ratio`
// fraction by `residual` is dropped (ties broken by index, so the choice is
// deterministic). reject_ratio <= 0 keeps all.
std::vector<std::size_t> keepBestPlanes(const std::vector<double>& residual, double reject_ratio);

}  // namespace hba::ba
