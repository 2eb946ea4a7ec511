#include "consistency.hpp"

#include <algorithm>
#include <cmath>

namespace hba::pyramid {

FixedPlaneMap::FixedPlaneMap(const std::vector<const PointCloud*>& scans,
                             const std::vector<Pose>& poses, const voxel::PlaneSettings& planes,
                             double reject_ratio, std::size_t regions)
    : problem_(ba::associate(scans, poses, planes, reject_ratio).problem) {
  const std::size_t frames = std::max<std::size_t>(1, poses.size());
  regions = std::clamp<std::size_t>(regions, 1, frames);
  for (std::size_t r = 0; r < regions; ++r) region_starts_.push_back(r * frames / regions);
  region_points_.assign(regions, 0.0);
  for (const ba::PlaneObservation& plane : problem_.planes()) {
    const std::size_t first = plane.clusters.front().frame;
    const std::size_t region = std::min(regions - 1, first * regions / frames);
    plane_region_.push_back(region);
    plane_points_.push_back(plane.pointCount());
    region_points_[region] += plane.pointCount();
    points_ += plane.pointCount();
  }
}

double FixedPlaneMap::rms(const std::vector<Pose>& poses) const {
  if (!(points_ > 0.0)) return 0.0;
  return std::sqrt(problem_.cost(poses) / points_);
}

std::vector<double> FixedPlaneMap::regionRms(const std::vector<Pose>& poses) const {
  const std::vector<double> costs = problem_.planeCosts(poses);
  std::vector<double> sums(region_points_.size(), 0.0);
  for (std::size_t p = 0; p < costs.size(); ++p) sums[plane_region_[p]] += costs[p];
  for (std::size_t r = 0; r < sums.size(); ++r) {
    sums[r] = region_points_[r] > 0.0 ? std::sqrt(sums[r] / region_points_[r]) : 0.0;
  }
  return sums;
}

}  // namespace hba::pyramid
