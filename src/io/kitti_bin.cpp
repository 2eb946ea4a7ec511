// KITTI velodyne .bin: records of four little-endian float32 (x y z
// intensity), no header. Reading is one file read plus the shared column loop.
#include "hba/io/kitti_bin.hpp"

#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "cloud_checks.hpp"
#include "file_bytes.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "point_columns.hpp"

namespace hba::io {
namespace {

[[noreturn]] void failPartialRecord(const std::filesystem::path& path, std::uintmax_t bytes) {
  failAt(path, "size " + std::to_string(bytes) +
                   " bytes is not a multiple of 16 (x y z intensity as float32): "
                   "truncated or not a KITTI scan");
}

// The file's bytes: one record a point.
std::string records(const std::filesystem::path& path, const PointCloud& cloud) {
  detail::requireOneIntensityPerPoint(cloud, path);
  std::string content(cloud.size() * kKittiPointBytes, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    // A KITTI record always carries an intensity; 0 stands for "none".
    const float record[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                             cloud.hasIntensity() ? cloud.intensity[i] : 0.0f};
    std::memcpy(&content[i * kKittiPointBytes], record, kKittiPointBytes);
  }
  return content;
}

}  // namespace

PointCloud readKittiBin(const std::filesystem::path& path) {
  const detail::FileBytes bytes = detail::readFileBytes(path);
  if (bytes.size() % kKittiPointBytes != 0) failPartialRecord(path, bytes.size());
  const auto column = [&](std::size_t index) {
    return detail::Column{bytes.data() + index * sizeof(float), kKittiPointBytes,
                          detail::ScalarType::Float32};
  };
  const detail::PointColumns columns{column(0), column(1), column(2), column(3), false};
  PointCloud cloud;
  detail::appendFinitePoints(columns, bytes.size() / kKittiPointBytes, cloud);
  return cloud;
}

void writeKittiBin(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::string content = records(path, cloud);
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void writeScratchKittiBin(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::string content = records(path, cloud);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.close();
  if (!out) failAt(path, "cannot write the scan (is the disk full?)");
}

std::uint64_t kittiBinPointCount(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) failAt(path, "cannot read the file size: " + ec.message());
  if (bytes % kKittiPointBytes != 0) failPartialRecord(path, bytes);
  return bytes / kKittiPointBytes;
}

}  // namespace hba::io
