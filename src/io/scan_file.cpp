// Dispatch on the file extension (case-insensitive: ".PCD" is common on
// Windows-made datasets).
#include "hba/io/scan_file.hpp"

#include "cloud_readers.hpp"
#include "cloud_view.hpp"
#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/wide_cloud.hpp"
#include "text_parsing.hpp"

namespace hba::io {
namespace {

std::optional<ScanFormat> formatOf(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  if (detail::equalsIgnoreCase(extension, ".pcd")) return ScanFormat::Pcd;
  if (detail::equalsIgnoreCase(extension, ".bin")) return ScanFormat::KittiBin;
  if (detail::equalsIgnoreCase(extension, ".ply")) return ScanFormat::Ply;
  if (detail::equalsIgnoreCase(extension, ".las")) return ScanFormat::Las;
  return std::nullopt;
}

}  // namespace

ScanFormat scanFormatFromExtension(const std::filesystem::path& path) {
  if (const auto format = formatOf(path)) return *format;
  failAt(path, "unknown scan format " + detail::quoteToken(path.extension().string()) +
                   " (hba reads .pcd, .bin, .ply and .las)");
}

bool isScanFile(const std::filesystem::path& path) { return formatOf(path).has_value(); }

PointCloud readScan(const std::filesystem::path& path) {
  switch (scanFormatFromExtension(path)) {
    case ScanFormat::Pcd:
      return readPcd(path);
    case ScanFormat::KittiBin:
      return readKittiBin(path);
    case ScanFormat::Ply:
      return readPly(path);
    case ScanFormat::Las:
      return readLas(path);
  }
  failAt(path, "unknown scan format");
}

void writeScan(const std::filesystem::path& path, const PointCloud& cloud) {
  switch (scanFormatFromExtension(path)) {
    case ScanFormat::Pcd:
      writePcd(path, cloud);
      break;
    case ScanFormat::KittiBin:
      writeKittiBin(path, cloud);
      break;
    case ScanFormat::Ply:
      writePly(path, cloud);
      break;
    case ScanFormat::Las:
      writeLas(path, cloud);
      break;
  }
}

WideCloud readScanWide(const std::filesystem::path& path) {
  return readScanWide(path, scanFormatFromExtension(path));
}

WideCloud readScanWide(const std::filesystem::path& path, ScanFormat format) {
  switch (format) {
    case ScanFormat::Pcd:
      return detail::readPcdAs<WideCloud>(path);
    case ScanFormat::KittiBin:
      return detail::readKittiBinAs<WideCloud>(path);
    case ScanFormat::Ply:
      return detail::readPlyAs<WideCloud>(path);
    case ScanFormat::Las:
      return detail::readLasAs<WideCloud>(path);
  }
  failAt(path, "unknown scan format");
}

void writeScanWide(const std::filesystem::path& path, const WideCloud& cloud) {
  const detail::CloudView view(cloud);
  switch (scanFormatFromExtension(path)) {
    case ScanFormat::Pcd:
      detail::writePcdView(path, view, PcdEncoding::Binary);
      break;
    case ScanFormat::KittiBin:
      detail::writeKittiBinView(path, view);
      break;
    case ScanFormat::Ply:
      detail::writePlyView(path, view, PlyEncoding::BinaryLittleEndian);
      break;
    case ScanFormat::Las:
      detail::writeLasView(path, view, {});
      break;
  }
}

}  // namespace hba::io
