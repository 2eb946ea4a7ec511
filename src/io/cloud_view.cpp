#include "cloud_view.hpp"

#include <cmath>
#include <string>

#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace {

// NaN is a float too (written as one, dropped by every reader).
bool isFloat(double value) {
  return std::isnan(value) || static_cast<double>(static_cast<float>(value)) == value;
}

// Whether any coordinate would change as a float32: one pass, at write time.
bool needsDouble(const WideCloud& cloud) {
  for (const Vec3& p : cloud.points) {
    if (!isFloat(p.x()) || !isFloat(p.y()) || !isFloat(p.z())) return true;
  }
  return false;
}

}  // namespace

CloudView::CloudView(const PointCloud& cloud)
    : size_(cloud.size()),
      narrow_(cloud.points.data()),
      origin_(cloud.origin),
      intensity_(cloud.intensity),
      time_(&cloud.time),
      wide_(!cloud.origin.isZero()) {}

CloudView::CloudView(const WideCloud& cloud)
    : size_(cloud.size()),
      wide_points_(cloud.points.data()),
      intensity_(cloud.intensity),
      wide_(needsDouble(cloud)) {}

void CloudView::requireOneValuePerPoint(const std::filesystem::path& path) const {
  if (hasIntensity() && intensity_.size() != size_) {
    failAt(path, "cannot write: the cloud has " + std::to_string(size_) + " points but " +
                     std::to_string(intensity_.size()) + " intensities");
  }
  if (hasTime() && time_->size() != size_) {
    failAt(path, "cannot write: the cloud has " + std::to_string(size_) + " points but " +
                     std::to_string(time_->size()) + " point times");
  }
}

}  // namespace hba::io::detail
