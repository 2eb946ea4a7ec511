#pragma once
// Gathers points out of a decoded buffer. Each coordinate is a "column": a
// first element and a fixed stride, which describes row-major records (PCD
// binary, KITTI, PLY binary) and column-major blocks (PCD binary_compressed)
// alike, so every binary reader shares one loop.
#include <cstddef>
#include <optional>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/io/wide_cloud.hpp"
#include "scalar_type.hpp"

namespace hba::io::detail {

struct Column {
  const char* first = nullptr;  // element of point 0
  std::size_t stride = 0;       // bytes from one point's element to the next
  ScalarType type = ScalarType::Float32;

  float at(std::size_t i, bool big_endian) const { return loadAsFloat(first + i * stride, type, big_endian); }
};

struct PointColumns {
  Column x, y, z;
  std::optional<Column> intensity;
  bool big_endian = false;
  std::optional<Column> time;  // each point's time, kept as stored (PointCloud::time)
};

// Appends the `count` points the columns describe, dropping any point with a
// NaN or infinite coordinate. The caller has checked that every element lies
// inside its buffer. Float64 coordinates keep their precision (addFinitePoint).
void appendFinitePoints(const PointColumns& columns, std::size_t count, PointCloud& cloud);
// The same points in double: any stored type exactly (readScanWide).
void appendFinitePoints(const PointColumns& columns, std::size_t count, WideCloud& cloud);

// Collects the points a reader decodes (x y z [intensity]), dropping those
// with a NaN or infinite coordinate. When the file stores coordinates as
// float64 (`wide`) they are held in double until finish(), which gives the
// cloud an origin when the bulk of its points (their per-axis median) lies
// more than 10 km out (a map in UTM or ECEF): points are then kept relative to
// it in whole metres, where floats would round them to decimetres. Neither a
// stray first point nor (0,0,0) placeholders decide the origin.
template <typename Cloud>
class PointCollector;

template <>
class PointCollector<PointCloud> {
 public:
  PointCollector(PointCloud& cloud, bool wide, bool with_intensity, bool with_time = false);
  // values: x y z intensity; `time` is kept when the collector was made with_time.
  void add(const double (&values)[4], double time = 0.0);
  void finish();

 private:
  PointCloud& cloud_;
  bool wide_, with_intensity_, with_time_;
  std::vector<Vec3> wide_points_;
  std::vector<float> wide_intensity_;
  std::vector<double> wide_time_;
};

// For a WideCloud every finite point goes in as decoded, in double.
template <>
class PointCollector<WideCloud> {
 public:
  PointCollector(WideCloud& cloud, bool /*wide*/, bool with_intensity, bool /*with_time*/ = false)
      : cloud_(cloud), with_intensity_(with_intensity) {}
  void add(const double (&values)[4], double /*time*/ = 0.0) {
    const Vec3 p(values[0], values[1], values[2]);
    if (!p.allFinite()) return;
    if (with_intensity_) {
      cloud_.add(p, static_cast<float>(values[3]));
    } else {
      cloud_.add(p);
    }
  }
  void finish() {}

 private:
  WideCloud& cloud_;
  bool with_intensity_;
};

template <typename Cloud>
PointCollector(Cloud&, bool, bool) -> PointCollector<Cloud>;
template <typename Cloud>
PointCollector(Cloud&, bool, bool, bool) -> PointCollector<Cloud>;

}  // namespace hba::io::detail
