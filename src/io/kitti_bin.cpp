// KITTI velodyne .bin: records of four little-endian float32 (x y z
// intensity), no header. Reading is one file read plus the shared column loop.
#include "hba/io/kitti_bin.hpp"

#include <cstring>
#include <string>

#include "cloud_checks.hpp"
#include "file_bytes.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "point_columns.hpp"

namespace hba::io {
namespace {
constexpr std::size_t kRecordBytes = 4 * sizeof(float);
}  // namespace

PointCloud readKittiBin(const std::filesystem::path& path) {
  const detail::FileBytes bytes = detail::readFileBytes(path);
  if (bytes.size() % kRecordBytes != 0) {
    failAt(path, "size " + std::to_string(bytes.size()) +
                     " bytes is not a multiple of 16 (x y z intensity as float32): "
                     "truncated or not a KITTI scan");
  }
  const auto column = [&](std::size_t index) {
    return detail::Column{bytes.data() + index * sizeof(float), kRecordBytes,
                          detail::ScalarType::Float32};
  };
  const detail::PointColumns columns{column(0), column(1), column(2), column(3), false};
  PointCloud cloud;
  detail::appendFinitePoints(columns, bytes.size() / kRecordBytes, cloud);
  return cloud;
}

void writeKittiBin(const std::filesystem::path& path, const PointCloud& cloud) {
  detail::requireOneIntensityPerPoint(cloud, path);
  std::string content(cloud.size() * kRecordBytes, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    // A KITTI record always carries an intensity; 0 stands for "none".
    const float record[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                             cloud.hasIntensity() ? cloud.intensity[i] : 0.0f};
    std::memcpy(&content[i * kRecordBytes], record, kRecordBytes);
  }
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace hba::io
