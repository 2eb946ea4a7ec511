#include "picture_points.hpp"

#include <cmath>

namespace hba::render {
namespace {

constexpr std::int64_t kHalfRange = std::int64_t{1} << 20;

}  // namespace

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
  constexpr std::uint64_t kOutside = ~std::uint64_t{0};
  thread_local std::vector<std::uint64_t> keys;
  thread_local std::vector<Vec3f> local;
  keys.resize(cloud.points.size());
  local.resize(cloud.points.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Vec3 q = R * cloud.points[i].cast<double>() + t;
    local[i] = q.cast<float>();
    std::uint64_t key = 0;
    for (int axis = 0; axis < 3; ++axis) {
      // Clamped for NaN and huge values, which then fall outside the range.
      const std::int64_t cell = voxel::VoxelKey::cell(q(axis) * inverse_voxel_);
      if (!(cell > -kHalfRange && cell < kHalfRange)) {
        key = kOutside;
        break;
      }
      key |= static_cast<std::uint64_t>(cell + kHalfRange) << (21 * axis);
    }
    keys[i] = key;
  }
  constexpr std::size_t kLookahead = 16;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i + kLookahead < keys.size()) index_.prefetch(keys[i + kLookahead]);
    if (keys[i] == kOutside || (i > 0 && keys[i] == keys[i - 1])) continue;
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
