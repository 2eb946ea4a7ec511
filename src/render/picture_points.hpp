#pragma once
// The points a picture draws (private to render): one per occupied voxel,
// the first that fell in it, found by a flat set of packed voxel keys.
// 25-40 bytes a voxel where a merged map with centroids takes over 100:
// pictures of long sequences stay small.
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/voxel/key_table.hpp"

namespace hba::render {

// A voxel's key packed into 64 bits (21 bits an axis) for the voxel of edge
// 1 / `inverse_voxel` holding `q`; kOutsidePackedRange more than 2^20
// voxels from the origin in any axis (or not finite).
inline constexpr std::uint64_t kOutsidePackedRange = ~std::uint64_t{0};
inline std::uint64_t packedVoxelKey(const Vec3& q, double inverse_voxel) {
  constexpr std::int64_t kHalfRange = std::int64_t{1} << 20;
  std::uint64_t key = 0;
  for (int axis = 0; axis < 3; ++axis) {
    // Clamped for NaN and huge values, which then fall outside the range.
    const std::int64_t cell = voxel::VoxelKey::cell(q(axis) * inverse_voxel);
    if (!(cell > -kHalfRange && cell < kHalfRange)) return kOutsidePackedRange;
    key |= static_cast<std::uint64_t>(cell + kHalfRange) << (21 * axis);
  }
  return key;
}

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
  voxel::PackedKeySet index_;  // packed voxel keys seen
  std::vector<Vec3f> points_;  // relative to origin_, in the order first hit
};

}  // namespace hba::render
