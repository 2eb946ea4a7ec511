#include "plane_overlap.hpp"

#include <algorithm>
#include <iterator>

namespace hba::closure {

double planeOverlap(const PointCloud& map, const std::vector<std::uint32_t>& shared_points,
                    const voxel::PlaneSettings& planes) {
  voxel::PlaneSettings alone = planes;
  alone.min_frames = 1;
  std::vector<std::uint32_t> own;
  for (const voxel::PlaneFeature& plane : voxel::extractPlanes({&map}, {Pose()}, alone)) {
    for (const voxel::PointRef& p : plane.points) own.push_back(p.index);
  }
  if (own.empty()) return 0.0;
  std::sort(own.begin(), own.end());
  std::vector<std::uint32_t> both;
  std::set_intersection(own.begin(), own.end(), shared_points.begin(), shared_points.end(),
                        std::back_inserter(both));
  return static_cast<double>(both.size()) / static_cast<double>(own.size());
}

}  // namespace hba::closure
