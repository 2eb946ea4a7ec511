#include "point_columns.hpp"

#include <algorithm>
#include <cmath>

namespace hba::io::detail {

namespace {

bool isPlainFloat(const Column& column, bool big_endian) {
  return column.type == ScalarType::Float32 && !big_endian;
}

// Moves the finite points of [start, end) to the front of that range (keeping
// their order) and drops the rest.
void dropNonFinite(PointCloud& cloud, std::size_t start) {
  const bool with_intensity = cloud.hasIntensity();
  std::size_t kept = start;
  for (std::size_t i = start; i < cloud.points.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;
    cloud.points[kept] = cloud.points[i];
    if (with_intensity) cloud.intensity[kept] = cloud.intensity[i];
    ++kept;
  }
  cloud.points.resize(kept);
  if (with_intensity) cloud.intensity.resize(kept);
}

// The common case (little-endian float32 everywhere): a straight copy with no
// type switch and no branch per point, then a compaction pass only in the
// rare cloud that holds NaN or infinite points.
template <bool kWithIntensity>
void appendFloat32(const PointColumns& c, std::size_t count, PointCloud& cloud) {
  const std::size_t start = cloud.points.size();
  cloud.points.resize(start + count);
  if constexpr (kWithIntensity) cloud.intensity.resize(start + count);
  Vec3f* points = cloud.points.data() + start;
  float* intensity = kWithIntensity ? cloud.intensity.data() + start : nullptr;
  bool all_finite = true;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3f p(loadUnaligned<float>(c.x.first + i * c.x.stride, false),
                  loadUnaligned<float>(c.y.first + i * c.y.stride, false),
                  loadUnaligned<float>(c.z.first + i * c.z.stride, false));
    points[i] = p;
    if constexpr (kWithIntensity) {
      intensity[i] = loadUnaligned<float>(c.intensity->first + i * c.intensity->stride, false);
    }
    // x - x is 0 for finite x and NaN otherwise; a sum of those stays 0 only
    // when all are finite, without a branch.
    all_finite &= ((p.x() - p.x()) + (p.y() - p.y()) + (p.z() - p.z())) == 0.0f;
  }
  if (!all_finite) dropNonFinite(cloud, start);
}

bool isFloat64(const Column& column) { return column.type == ScalarType::Float64; }

void appendWide(const PointColumns& c, std::size_t count, PointCloud& cloud) {
  const bool be = c.big_endian;
  PointCollector collector(cloud, true, c.intensity.has_value());
  for (std::size_t i = 0; i < count; ++i) {
    const double values[4] = {loadAsDouble(c.x.first + i * c.x.stride, c.x.type, be),
                              loadAsDouble(c.y.first + i * c.y.stride, c.y.type, be),
                              loadAsDouble(c.z.first + i * c.z.stride, c.z.type, be),
                              c.intensity ? c.intensity->at(i, be) : 0.0};
    collector.add(values);
  }
  collector.finish();
}

// A raw sweep's points with their times, each value in double until stored.
void appendTimed(const PointColumns& c, std::size_t count, PointCloud& cloud) {
  const bool be = c.big_endian;
  cloud.time.reserve(cloud.time.size() + count);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3f p(static_cast<float>(loadAsDouble(c.x.first + i * c.x.stride, c.x.type, be)),
                  static_cast<float>(loadAsDouble(c.y.first + i * c.y.stride, c.y.type, be)),
                  static_cast<float>(loadAsDouble(c.z.first + i * c.z.stride, c.z.type, be)));
    if (!p.allFinite()) continue;
    if (c.intensity) {
      cloud.add(p, c.intensity->at(i, be));
    } else {
      cloud.add(p);
    }
    cloud.time.push_back(loadAsDouble(c.time->first + i * c.time->stride, c.time->type, be));
  }
}

void appendAnyType(const PointColumns& c, std::size_t count, PointCloud& cloud) {
  if (isFloat64(c.x) || isFloat64(c.y) || isFloat64(c.z)) return appendWide(c, count, cloud);
  const bool be = c.big_endian;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3f p(c.x.at(i, be), c.y.at(i, be), c.z.at(i, be));
    if (!p.allFinite()) continue;
    if (c.intensity) {
      cloud.add(p, c.intensity->at(i, be));
    } else {
      cloud.add(p);
    }
  }
}

}  // namespace

PointCollector<PointCloud>::PointCollector(PointCloud& cloud, bool wide, bool with_intensity, bool with_time)
    : cloud_(cloud), wide_(wide), with_intensity_(with_intensity), with_time_(with_time) {}

void PointCollector<PointCloud>::add(const double (&values)[4], double time) {
  const Vec3 p(values[0], values[1], values[2]);
  if (!p.allFinite()) return;
  if (wide_) {
    wide_points_.push_back(p);
    if (with_intensity_) wide_intensity_.push_back(static_cast<float>(values[3]));
    if (with_time_) wide_time_.push_back(time);
    return;
  }
  const Vec3f narrow = p.cast<float>();
  if (!narrow.allFinite()) return;  // a float64 too large for a float
  if (with_intensity_) {
    cloud_.add(narrow, static_cast<float>(values[3]));
  } else {
    cloud_.add(narrow);
  }
  if (with_time_) cloud_.time.push_back(time);
}

void PointCollector<PointCloud>::finish() {
  if (wide_points_.empty()) return;
  if (cloud_.empty() && cloud_.origin.isZero()) cloud_.origin = farCloudOrigin(wide_points_);
  cloud_.reserve(cloud_.size() + wide_points_.size(), with_intensity_);
  for (std::size_t i = 0; i < wide_points_.size(); ++i) {
    const Vec3f relative = (wide_points_[i] - cloud_.origin).cast<float>();
    if (!relative.allFinite()) continue;  // too large for a float
    if (with_intensity_) {
      cloud_.add(relative, wide_intensity_[i]);
    } else {
      cloud_.add(relative);
    }
    if (with_time_) cloud_.time.push_back(wide_time_[i]);
  }
  wide_points_.clear();
  wide_intensity_.clear();
  wide_time_.clear();
}

void appendFinitePoints(const PointColumns& columns, std::size_t count, PointCloud& cloud) {
  cloud.reserve(cloud.size() + count, columns.intensity.has_value());
  const bool be = columns.big_endian;
  if (columns.time) return appendTimed(columns, count, cloud);
  const bool all_float = isPlainFloat(columns.x, be) && isPlainFloat(columns.y, be) &&
                         isPlainFloat(columns.z, be) &&
                         (!columns.intensity || isPlainFloat(*columns.intensity, be));
  if (!all_float) {
    appendAnyType(columns, count, cloud);
  } else if (columns.intensity) {
    appendFloat32<true>(columns, count, cloud);
  } else {
    appendFloat32<false>(columns, count, cloud);
  }
}

void appendFinitePoints(const PointColumns& columns, std::size_t count, WideCloud& cloud) {
  cloud.reserve(cloud.size() + count, columns.intensity.has_value());
  const bool be = columns.big_endian;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 p(loadAsDouble(columns.x.first + i * columns.x.stride, columns.x.type, be),
                 loadAsDouble(columns.y.first + i * columns.y.stride, columns.y.type, be),
                 loadAsDouble(columns.z.first + i * columns.z.stride, columns.z.type, be));
    if (!p.allFinite()) continue;
    if (columns.intensity) {
      cloud.add(p, columns.intensity->at(i, be));
    } else {
      cloud.add(p);
    }
  }
}

}  // namespace hba::io::detail

namespace hba::io {

Vec3 farCloudOrigin(const std::vector<Vec3>& points) {
  constexpr double kFar = 1.0e4;      // m; floats are 1 mm apart there
  constexpr double kOnEarth = 1.0e8;  // m; beyond that stray values, not a place
  Vec3 median;
  std::vector<double> axis;
  axis.reserve(points.size());
  for (int a = 0; a < 3; ++a) {
    axis.clear();
    for (const Vec3& p : points) {
      if (p.allFinite()) axis.push_back(p[a]);
    }
    if (axis.empty()) return Vec3::Zero();
    std::nth_element(axis.begin(), axis.begin() + static_cast<std::ptrdiff_t>(axis.size() / 2), axis.end());
    median[a] = axis[axis.size() / 2];
  }
  const double distance = median.cwiseAbs().maxCoeff();
  return distance > kFar && distance < kOnEarth ? Vec3(median.array().round().matrix()) : Vec3::Zero();
}

}  // namespace hba::io
