#include "hba/core/point_cloud.hpp"

namespace hba {

void PointCloud::reserve(std::size_t n, bool with_intensity) {
  points.reserve(n);
  if (with_intensity) intensity.reserve(n);
}

void PointCloud::clear() {
  points.clear();
  intensity.clear();
  time.clear();
  origin = Vec3::Zero();
}

}  // namespace hba
