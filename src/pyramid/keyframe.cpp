#include "keyframe.hpp"

#include "hba/voxel/downsample.hpp"

namespace hba::pyramid {

PointCloud buildKeyframe(const std::vector<const PointCloud*>& clouds, const std::vector<Pose>& optimized,
                         const std::vector<std::vector<std::uint32_t>>& plane_point_indices, double voxel) {
  std::size_t total = 0;
  for (const auto& indices : plane_point_indices) total += indices.size();
  const bool with_intensity = !clouds.empty() && clouds.front()->hasIntensity();
  PointCloud merged;
  merged.reserve(total, with_intensity);

  const Pose first_inverse = optimized.front().inverse();
  for (std::size_t k = 0; k < clouds.size() && k < plane_point_indices.size(); ++k) {
    const PointCloud& cloud = *clouds[k];
    const Pose to_first = first_inverse * optimized[k];
    const Eigen::Matrix3f R = to_first.R().cast<float>();
    const Eigen::Vector3f t = to_first.t.cast<float>();
    for (const std::uint32_t index : plane_point_indices[k]) {
      const Vec3f p = R * cloud.points[index] + t;
      if (with_intensity && cloud.hasIntensity()) {
        merged.add(p, cloud.intensity[index]);
      } else if (!with_intensity) {
        merged.add(p);
      } else {
        merged.add(p, 0.0f);
      }
    }
  }
  // Ten overlapping scans at twice their voxel: about 5 points a cell.
  return voxel::downsample(merged, voxel, 4);
}

}  // namespace hba::pyramid
