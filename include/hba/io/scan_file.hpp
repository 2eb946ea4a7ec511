#pragma once
// Reads or writes a scan in the format its extension names
// (scan_formats.hpp lists them).
#include <filesystem>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

bool isScanFile(const std::filesystem::path& path);  // an extension of scanFormats()
// Throw hba::Error naming the file (an extension hba does not read, a bad file).
PointCloud readScan(const std::filesystem::path& path);
void writeScan(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace hba::io
