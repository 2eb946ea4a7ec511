#include "point_columns.hpp"

#include <cmath>

namespace hba::io::detail {

namespace {

bool isPlainFloat(const Column& column, bool big_endian) {
  return column.type == ScalarType::Float32 && !big_endian;
}

// The common case (little-endian float32 everywhere) without a type switch per
// value: this loop runs at memory speed on real scans.
template <bool kWithIntensity>
void appendFloat32(const PointColumns& c, std::size_t count, PointCloud& cloud) {
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3f p(loadUnaligned<float>(c.x.first + i * c.x.stride, false),
                  loadUnaligned<float>(c.y.first + i * c.y.stride, false),
                  loadUnaligned<float>(c.z.first + i * c.z.stride, false));
    if (!p.allFinite()) continue;
    if constexpr (kWithIntensity) {
      cloud.add(p, loadUnaligned<float>(c.intensity->first + i * c.intensity->stride, false));
    } else {
      cloud.add(p);
    }
  }
}

void appendAnyType(const PointColumns& c, std::size_t count, PointCloud& cloud) {
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

void appendFinitePoints(const PointColumns& columns, std::size_t count, PointCloud& cloud) {
  cloud.reserve(cloud.size() + count, columns.intensity.has_value());
  const bool be = columns.big_endian;
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

}  // namespace hba::io::detail
