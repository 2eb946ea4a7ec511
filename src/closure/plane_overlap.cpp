#include "plane_overlap.hpp"

#include <algorithm>
#include <iterator>

namespace hba::closure {

double planeOverlap(const PointCloud& map, const std::vector<std::uint32_t>& shared_points,
                    const voxel::PlaneSettings& planes) {
  voxel::PlaneSettings alone = planes;
  alone.min_frames = 1;
  // One cloud: its planes' point indices, ascending.
  const std::vector<std::uint32_t> own =
      voxel::extractPlanes({&map}, {Pose()}, alone).pointIndicesPerScan()[0];
  if (own.empty()) return 0.0;
  std::vector<std::uint32_t> both;
  std::set_intersection(own.begin(), own.end(), shared_points.begin(), shared_points.end(),
                        std::back_inserter(both));
  return static_cast<double>(both.size()) / static_cast<double>(own.size());
}

}  // namespace hba::closure
