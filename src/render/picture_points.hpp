#pragma once
// The points a picture draws (private to render): one per occupied voxel,
// the first that fell in it, found by a flat set of packed voxel keys.
// 25-40 bytes a voxel where a merged map with centroids takes over 100:
// pictures of long sequences stay small.
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/voxel/voxel_index.hpp"

namespace hba::render {

class PicturePoints {
 public:
  // Points are kept relative to `origin` (float precision near it); voxels
  // more than 2^20 voxels from it in any axis are left out.
  // `expected`: voxels to make room for at once (a guess; it grows as needed).
  PicturePoints(double voxel, const Vec3& origin, std::size_t expected = 0);
  // `cloud` (relative to its own origin) moved into the world by `pose`.
  void add(const PointCloud& cloud, const Pose& pose);
  std::size_t size() const { return points_.size(); }
  // The points, with the constructor's `origin` as their PointCloud::origin,
  // moved out: the set is empty afterwards and its memory freed.
  PointCloud take();

 private:
  double inverse_voxel_;
  Vec3 origin_;
  voxel::PackedVoxelSet index_;  // packed voxel keys seen
  std::vector<Vec3f> points_;    // relative to origin_, in the order first hit
};

}  // namespace hba::render
