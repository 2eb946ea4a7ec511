// A PointCloud2 of any field layout into a PointCloud: each field read by
// its own type, offset and byte order.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "hba/core/error.hpp"
#include "hba/rec/ros_messages.hpp"

namespace hba::rec {
namespace {

std::size_t sizeOf(std::uint8_t datatype) {
  switch (datatype) {
    case 1:
    case 2:
      return 1;
    case 3:
    case 4:
      return 2;
    case 5:
    case 6:
    case 7:
      return 4;
    case 8:
      return 8;
    default:
      return 0;
  }
}

template <typename T>
double as(const std::uint8_t* p, bool swap) {
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return static_cast<double>(value);
}

// One field of the points, ready to read.
struct Column {
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  bool swap = false;
  double read(const std::uint8_t* point) const {
    const std::uint8_t* p = point + offset;
    switch (datatype) {
      case 1:
        return as<std::int8_t>(p, false);
      case 2:
        return as<std::uint8_t>(p, false);
      case 3:
        return as<std::int16_t>(p, swap);
      case 4:
        return as<std::uint16_t>(p, swap);
      case 5:
        return as<std::int32_t>(p, swap);
      case 6:
        return as<std::uint32_t>(p, swap);
      case 7:
        return as<float>(p, swap);
      default:
        return as<double>(p, swap);
    }
  }
};

const PointField* findField(const PointCloud2View& cloud, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    for (const PointField& field : cloud.fields) {
      if (field.name == name) return &field;
    }
  }
  return nullptr;
}

std::string fieldNames(const PointCloud2View& cloud) {
  std::string names;
  for (const PointField& field : cloud.fields) names += (names.empty() ? "" : ", ") + field.name;
  return names.empty() ? "none" : names;
}

Column columnOf(const PointCloud2View& cloud, const PointField& field, const std::string& what) {
  const std::size_t size = sizeOf(field.datatype);
  if (size == 0)
    throw Error(what + ": field '" + field.name + "' has unknown datatype " + std::to_string(field.datatype));
  if (field.offset + size > cloud.point_step) {
    throw Error(what + ": field '" + field.name + "' (offset " + std::to_string(field.offset) +
                ") lies outside the point's " + std::to_string(cloud.point_step) + " bytes");
  }
  return Column{field.offset, field.datatype, cloud.big_endian};
}

}  // namespace

PointCloud toPointCloud(const PointCloud2View& cloud, const std::string& what) {
  const PointField* x = findField(cloud, {"x"});
  const PointField* y = findField(cloud, {"y"});
  const PointField* z = findField(cloud, {"z"});
  if (!x || !y || !z)
    throw Error(what + ": the cloud has no x, y and z fields (it has " + fieldNames(cloud) + ")");
  const Column cx = columnOf(cloud, *x, what), cy = columnOf(cloud, *y, what), cz = columnOf(cloud, *z, what);
  const PointField* intensity = findField(cloud, {"intensity", "reflectivity", "i"});
  Column ci;
  if (intensity) ci = columnOf(cloud, *intensity, what);
  const PointField* time = nullptr;
  for (const char* name : kPointTimeFields) {
    if (!time) time = findField(cloud, {name});
  }
  Column ct;
  if (time) ct = columnOf(cloud, *time, what);

  PointCloud out;
  out.reserve(std::size_t{cloud.height} * cloud.width, intensity != nullptr);
  if (time) out.time.reserve(std::size_t{cloud.height} * cloud.width);
  // Rows of no points: a width of 0 with a height of 4e9 would loop for seconds.
  const std::uint32_t rows = cloud.width == 0 ? 0 : cloud.height;
  for (std::uint32_t row = 0; row < rows; ++row) {
    const std::uint8_t* start = cloud.data + std::size_t{row} * cloud.row_step;
    for (std::uint32_t col = 0; col < cloud.width; ++col) {
      const std::uint8_t* point = start + std::size_t{col} * cloud.point_step;
      const Vec3f p(static_cast<float>(cx.read(point)), static_cast<float>(cy.read(point)),
                    static_cast<float>(cz.read(point)));
      if (!p.allFinite()) continue;
      if (intensity) {
        out.add(p, static_cast<float>(ci.read(point)));
      } else {
        out.add(p);
      }
      if (time) out.time.push_back(ct.read(point));
    }
  }
  return out;
}

}  // namespace hba::rec
