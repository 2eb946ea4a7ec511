#include "picture_points.hpp"

#include <cmath>

namespace hba::render {
namespace {

constexpr std::int64_t kHalfRange = std::int64_t{1} << 20;

}  // namespace

PicturePoints::PicturePoints(double voxel, const Vec3& origin) : voxel_(voxel), origin_(origin) {}

void PicturePoints::add(const PointCloud& cloud, const Pose& pose) {
  const Mat3 R = pose.R();
  const Vec3 t = pose * cloud.origin - origin_;
  for (const Vec3f& p : cloud.points) {
    const Vec3 local = R * p.cast<double>() + t;
    std::uint64_t key = 0;
    bool in_range = true;
    for (int axis = 0; axis < 3; ++axis) {
      const double cell = std::floor(local(axis) / voxel_);
      // Also false for NaN.
      in_range = in_range && cell > -static_cast<double>(kHalfRange) && cell < static_cast<double>(kHalfRange);
      if (!in_range) break;
      key |= static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + kHalfRange) << (21 * axis);
    }
    if (!in_range) continue;
    bool inserted = false;
    const std::uint32_t number = insert(key + 1, inserted);
    if (inserted) points_[number] = local.cast<float>();
  }
}

std::uint32_t PicturePoints::insert(std::uint64_t key, bool& inserted) {
  if (2 * (points_.size() + 1) > slots_.size()) grow();
  std::size_t s = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 20) & mask_;
  while (slots_[s].key != 0) {
    if (slots_[s].key == key) {
      inserted = false;
      return slots_[s].number;
    }
    s = (s + 1) & mask_;
  }
  slots_[s] = {key, static_cast<std::uint32_t>(points_.size())};
  points_.emplace_back();
  inserted = true;
  return slots_[s].number;
}

void PicturePoints::grow() {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(old.empty() ? 1024 : 2 * old.size(), Slot{});
  mask_ = slots_.size() - 1;
  for (const Slot& slot : old) {
    if (slot.key == 0) continue;
    std::size_t s = static_cast<std::size_t>((slot.key * 0x9E3779B97F4A7C15ULL) >> 20) & mask_;
    while (slots_[s].key != 0) s = (s + 1) & mask_;
    slots_[s] = slot;
  }
}

PointCloud PicturePoints::cloud() const {
  PointCloud out;
  out.origin = origin_;
  out.points = points_;
  return out;
}

}  // namespace hba::render
