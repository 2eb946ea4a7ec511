#pragma once
// Reads or writes a scan in the format its extension names (.pcd, .bin, .ply, .las).
#include <filesystem>
#include <string>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

enum class ScanFormat { Pcd, KittiBin, Ply, Las };

// Throws hba::Error for an extension hba does not read.
ScanFormat scanFormatFromExtension(const std::filesystem::path& path);
bool isScanFile(const std::filesystem::path& path);  // .pcd, .bin, .ply or .las
PointCloud readScan(const std::filesystem::path& path);
void writeScan(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace hba::io
