// KITTI velodyne .bin: records of four little-endian float32 (x y z
// intensity), no header. Reading is one file read plus the shared column loop.
#include "hba/io/kitti_bin.hpp"

#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "cloud_readers.hpp"
#include "cloud_view.hpp"
#include "file_bytes.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"
#include "point_columns.hpp"

namespace hba::io {
namespace {

[[noreturn]] void failPartialRecord(const std::filesystem::path& path, std::uintmax_t bytes) {
  failAt(path, "size " + std::to_string(bytes) +
                   " bytes is not a multiple of 16 (x y z intensity as float32): "
                   "truncated or not a KITTI scan");
}

// The file's bytes: one record a point. A .bin stores float32 and nothing
// else, so a coordinate a float would round (a map far out, a double) is
// refused rather than written somewhere else.
std::string records(const std::filesystem::path& path, const detail::CloudView& cloud) {
  cloud.requireOneValuePerPoint(path);
  std::string content(cloud.size() * kKittiPointBytes, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 world = cloud.world(i);
    const Vec3f p = world.cast<float>();
    if (world.allFinite() && p.cast<double>() != world) {
      failAt(path, "cannot write point " + std::to_string(i) + " (" +
                       fmt::format("{} {} {}", world.x(), world.y(), world.z()) +
                       ") exactly: a .bin stores float32 x y z; write " + scanFormatList(true) +
                       " to keep it");
    }
    // A KITTI record always carries an intensity; 0 stands for "none".
    const float record[4] = {p.x(), p.y(), p.z(), cloud.hasIntensity() ? cloud.intensity(i) : 0.0f};
    std::memcpy(&content[i * kKittiPointBytes], record, kKittiPointBytes);
  }
  return content;
}

}  // namespace

namespace detail {

template <typename Cloud>
Cloud readKittiBinAs(const std::filesystem::path& path) {
  const FileBytes bytes = readFileBytes(path);
  if (bytes.size() % kKittiPointBytes != 0) failPartialRecord(path, bytes.size());
  const auto column = [&](std::size_t index) {
    return Column{bytes.data() + index * sizeof(float), kKittiPointBytes, ScalarType::Float32};
  };
  const PointColumns columns{column(0), column(1), column(2), column(3), false, std::nullopt};
  Cloud cloud;
  appendFinitePoints(columns, bytes.size() / kKittiPointBytes, cloud);
  return cloud;
}

template PointCloud readKittiBinAs(const std::filesystem::path&);
template WideCloud readKittiBinAs(const std::filesystem::path&);

}  // namespace detail

PointCloud readKittiBin(const std::filesystem::path& path) {
  return detail::readKittiBinAs<PointCloud>(path);
}

namespace detail {

void writeKittiBinView(const std::filesystem::path& path, const CloudView& cloud) {
  const std::string content = records(path, cloud);
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace detail

void writeKittiBin(const std::filesystem::path& path, const PointCloud& cloud) {
  detail::writeKittiBinView(path, detail::CloudView(cloud));
}

void writeScratchKittiBin(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::string content = records(path, detail::CloudView(cloud));
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
