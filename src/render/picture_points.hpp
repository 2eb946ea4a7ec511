#pragma once
// The points a picture draws (private to render): one per occupied voxel,
// the first that fell in it, kept beside a flat hash set of packed voxel
// keys. About 40 bytes a voxel where a merged map with centroids takes over
// 100: pictures of long sequences stay small.
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::render {

class PicturePoints {
 public:
  // Points are kept relative to `origin` (float precision near it); voxels
  // more than 2^20 voxels from it in any axis are left out.
  PicturePoints(double voxel, const Vec3& origin);
  // `cloud` (relative to its own origin) moved into the world by `pose`.
  void add(const PointCloud& cloud, const Pose& pose);
  std::size_t size() const { return points_.size(); }
  // The points, with origin() as their PointCloud::origin.
  PointCloud cloud() const;

 private:
  // The number of `key`'s voxel; a new one gets size() and `inserted`.
  std::uint32_t insert(std::uint64_t key, bool& inserted);
  void grow();

  double voxel_;
  Vec3 origin_;
  struct Slot {
    std::uint64_t key = 0;  // packed key + 1; 0 = empty
    std::uint32_t number = 0;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::vector<Vec3f> points_;  // relative to origin_, in the order first hit
};

}  // namespace hba::render
