#pragma once
// The self-check of hba optimize: how crisp the map is with given poses,
// measured on one fixed set of planes (found at the input poses, finest
// voxel) so that the input, the hierarchy's and the final poses are
// compared like for like; in total and per stretch of the trajectory.
#include <cstddef>
#include <vector>

#include "hba/ba/association.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::pyramid {

class FixedPlaneMap {
 public:
  // Planes found at `poses` with the refinement's plane settings.
  FixedPlaneMap(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                const voxel::PlaneSettings& planes, double reject_ratio, std::size_t regions);

  std::size_t planes() const { return problem_.numPlanes(); }
  std::size_t regions() const { return region_points_.size(); }
  double points() const { return points_; }
  // RMS point-to-plane distance (m) over all planes, and per region (planes
  // belong to the region of their first observing frame; a region without
  // planes reads 0).
  double rms(const std::vector<Pose>& poses) const;
  std::vector<double> regionRms(const std::vector<Pose>& poses) const;
  // First frame of each region.
  const std::vector<std::size_t>& regionStarts() const { return region_starts_; }

 private:
  ba::PlaneProblem problem_;  // the clusters only: the points are not kept
  std::vector<std::size_t> plane_region_;
  std::vector<double> plane_points_;
  std::vector<double> region_points_;
  std::vector<std::size_t> region_starts_;
  double points_ = 0.0;
};

}  // namespace hba::pyramid
