// Scans by their file's extension (case-insensitive: ".PCD" is common on
// Windows-made datasets), through the table of formats.
#include "hba/io/scan_file.hpp"

#include "hba/io/scan_file_summary.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::io {

bool isScanFile(const std::filesystem::path& path) { return findScanFormat(path) != nullptr; }

PointCloud readScan(const std::filesystem::path& path) { return scanFormatOf(path).read(path); }

void writeScan(const std::filesystem::path& path, const PointCloud& cloud) {
  scanFormatOf(path).write(path, cloud);
}

WideCloud readScanWide(const std::filesystem::path& path) { return scanFormatOf(path).read_wide(path); }

void writeScanWide(const std::filesystem::path& path, const WideCloud& cloud) {
  scanFormatOf(path).write_wide(path, cloud);
}

std::uint64_t storedPointCount(const std::filesystem::path& path) {
  return scanFormatOf(path).stored_points(path);
}

ScanFileFields describeScanFields(const std::filesystem::path& path) {
  return scanFormatOf(path).describe(path);
}

}  // namespace hba::io
