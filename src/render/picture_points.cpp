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
  for (const Vec3f& p : cloud.points) {
    const Vec3 local = R * p.cast<double>() + t;
    std::uint64_t key = 0;
    bool in_range = true;
    for (int axis = 0; axis < 3; ++axis) {
      const double cell = std::floor(local(axis) * inverse_voxel_);
      // Also false for NaN.
      in_range = in_range && cell > -static_cast<double>(kHalfRange) && cell < static_cast<double>(kHalfRange);
      if (!in_range) break;
      key |= static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + kHalfRange) << (21 * axis);
    }
    if (!in_range) continue;
    bool inserted = false;
    index_.insert(key, inserted);
    if (inserted) points_.push_back(local.cast<float>());
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
