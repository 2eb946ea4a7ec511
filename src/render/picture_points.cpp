#include "picture_points.hpp"

#include <cmath>

namespace hba::render {

PicturePoints::PicturePoints(double voxel, const Vec3& origin, std::size_t expected)
    : inverse_voxel_(1.0 / voxel), origin_(origin) {
  index_.reserve(expected);
  points_.reserve(expected);
}

void PicturePoints::add(const PointCloud& cloud, const Pose& pose) {
  const Mat3 R = pose.R();
  const Vec3 t = pose * cloud.origin - origin_;
  // Keys first, then the inserts, each prefetching the slot of a key a few
  // points ahead. A point in the voxel of the point before it (scans come
  // ring by ring) is not new.
  thread_local std::vector<std::uint64_t> keys;
  thread_local std::vector<Vec3f> local;
  keys.resize(cloud.points.size());
  local.resize(cloud.points.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Vec3 q = R * cloud.points[i].cast<double>() + t;
    local[i] = q.cast<float>();
    keys[i] = packedVoxelKey(q, inverse_voxel_);
  }
  constexpr std::size_t kLookahead = 16;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i + kLookahead < keys.size()) index_.prefetch(keys[i + kLookahead]);
    if (keys[i] == kOutsidePackedRange || (i > 0 && keys[i] == keys[i - 1])) continue;
    if (index_.insert(keys[i])) points_.push_back(local[i]);
  }
}

PointCloud PicturePoints::take() {
  PointCloud out;
  out.origin = origin_;
  out.points = std::move(points_);
  points_ = {};
  index_ = {};
  return out;
}

}  // namespace hba::render
