#pragma once
// Gathers points out of a decoded buffer. Each coordinate is a "column": a
// first element and a fixed stride, which describes row-major records (PCD
// binary, KITTI, PLY binary) and column-major blocks (PCD binary_compressed)
// alike, so every binary reader shares one loop.
#include <cstddef>
#include <optional>

#include "hba/core/point_cloud.hpp"
#include "scalar_type.hpp"

namespace hba::io::detail {

struct Column {
  const char* first = nullptr;  // element of point 0
  std::size_t stride = 0;       // bytes from one point's element to the next
  ScalarType type = ScalarType::Float32;

  float at(std::size_t i, bool big_endian) const {
    return loadAsFloat(first + i * stride, type, big_endian);
  }
};

struct PointColumns {
  Column x, y, z;
  std::optional<Column> intensity;
  bool big_endian = false;
};

// Appends the `count` points the columns describe, dropping any point with a
// NaN or infinite coordinate. The caller has checked that every element lies
// inside its buffer. Float64 coordinates keep their precision (addFinitePoint).
void appendFinitePoints(const PointColumns& columns, std::size_t count, PointCloud& cloud);

// Appends x y z [intensity] unless a coordinate is NaN or infinite. When the
// file stores coordinates as float64 (`wide`), the first point further than
// 10 km from the origin (a map in UTM or ECEF) sets the cloud's origin to its
// whole metres, and points are kept relative to it: floats would otherwise
// round them to decimetres.
void addFinitePoint(const double (&values)[4], bool with_intensity, bool wide, PointCloud& cloud);

}  // namespace hba::io::detail
