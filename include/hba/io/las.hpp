#pragma once
// LAS (ASPRS LiDAR exchange format). Reads versions 1.0 to 1.4, point data
// record formats 0 to 10 (x, y, z and intensity; every other field is
// skipped); writes LAS 1.4 with point data record format 6. LAZ (compressed)
// files are refused with an error that says so.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/types.hpp"

namespace hba::io {

// The public header fields hba checks and reports.
struct LasHeader {
  int version_major = 1;
  int version_minor = 4;
  int point_format = 6;
  std::uint16_t header_size = 0;
  std::uint32_t point_data_offset = 0;  // byte offset of the first point record
  std::uint32_t vlr_count = 0;
  std::uint16_t record_length = 0;  // bytes per point record
  std::uint64_t point_count = 0;    // the 64-bit count (1.4) or the legacy one
  std::uint32_t legacy_point_count = 0;
  Vec3 scale = Vec3::Ones();
  Vec3 offset = Vec3::Zero();
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  std::string generating_software;
};

// Per-point values the LAS writer can store beyond a PointCloud's fields:
// each vector is empty (write 0) or has one value per point.
struct LasPointExtras {
  // Stored as the point source ID (uint16): indices above 65535 are written
  // as 65535, which then means "scan 65535 or later".
  std::vector<std::uint32_t> scan_index;
  std::vector<double> gps_time;  // seconds, as the GPS time field
};

// Parses and checks the public header only (cheap: for `hba info`). Throws hba::Error.
LasHeader readLasHeader(const std::filesystem::path& path);
// Points as x y z intensity; far-out coordinates (UTM) get a cloud origin.
PointCloud readLas(const std::filesystem::path& path);
// Writes LAS 1.4, point format 6, x y z in millimetres (scale 0.001) from an
// offset at the cloud's centre in whole metres, atomically. Throws hba::Error.
void writeLas(const std::filesystem::path& path, const PointCloud& cloud, const LasPointExtras& extras = {});

}  // namespace hba::io
