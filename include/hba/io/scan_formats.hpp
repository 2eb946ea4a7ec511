#pragma once
// The scan formats hba reads and writes, one entry each: the extension
// picks the entry, and every message that lists the formats takes the list
// from here. A new format is one entry (src/io/scan_formats.cpp).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/io/scan_file_summary.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::io {

struct ScanFormat {
  const char* extension;  // ".pcd"; matched case-insensitively
  const char* name;       // "PCD", for messages
  // A map in world coordinates (UTM) is written without rounding: maps and
  // writeScanWide may use the format.
  bool keeps_doubles;
  PointCloud (*read)(const std::filesystem::path& path);
  void (*write)(const std::filesystem::path& path, const PointCloud& cloud);
  // Each coordinate as the file stores it (wide_cloud.hpp).
  WideCloud (*read_wide)(const std::filesystem::path& path);
  void (*write_wide)(const std::filesystem::path& path, const WideCloud& cloud);
  // For `hba info`: points stored, and fields and encoding, read as cheaply
  // as the format allows.
  std::uint64_t (*stored_points)(const std::filesystem::path& path);
  ScanFileFields (*describe)(const std::filesystem::path& path);
};

const std::vector<ScanFormat>& scanFormats();
// The format of `path` by its extension; null for none.
const ScanFormat* findScanFormat(const std::filesystem::path& path);
// The same; throws hba::Error naming the file and the formats hba reads.
const ScanFormat& scanFormatOf(const std::filesystem::path& path);
// ".pcd, .bin, .ply, .las or .xyz" (only those that keep doubles: for maps).
std::string scanFormatList(bool keeping_doubles = false);

}  // namespace hba::io
