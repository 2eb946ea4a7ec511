// One switch over the scan formats for the summary `hba info` prints.
#include "hba/io/scan_file_summary.hpp"

#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/scan_file.hpp"

namespace hba::io {
namespace {

std::string pcdEncodingName(PcdEncoding encoding) {
  switch (encoding) {
    case PcdEncoding::Ascii:
      return "PCD ascii";
    case PcdEncoding::Binary:
      return "PCD binary";
    case PcdEncoding::BinaryCompressed:
      return "PCD binary_compressed";
  }
  return "PCD";
}

}  // namespace

std::uint64_t storedPointCount(const std::filesystem::path& path) {
  switch (scanFormatFromExtension(path)) {
    case ScanFormat::Pcd:
      return readPcdHeader(path).points;
    case ScanFormat::KittiBin:
      return kittiBinPointCount(path);
    case ScanFormat::Ply:
      return readScan(path).size();
    case ScanFormat::Las:
      return readLasHeader(path).point_count;
  }
  failAt(path, "unknown scan format");
}

ScanFileFields describeScanFields(const std::filesystem::path& path) {
  ScanFileFields out;
  switch (scanFormatFromExtension(path)) {
    case ScanFormat::Pcd: {
      const PcdHeader header = readPcdHeader(path);
      for (const PcdField& field : header.fields) {
        out.fields.push_back(field.count == 1 ? field.name
                                              : field.name + "[" + std::to_string(field.count) + "]");
      }
      out.encoding = pcdEncodingName(header.encoding);
      break;
    }
    case ScanFormat::KittiBin:
      out.fields = {"x", "y", "z", "intensity"};
      out.encoding = "KITTI float32";
      break;
    case ScanFormat::Ply: {
      out.fields = {"x", "y", "z"};
      if (readScan(path).hasIntensity()) out.fields.push_back("intensity");
      out.encoding = "PLY";
      break;
    }
    case ScanFormat::Las: {
      const LasHeader header = readLasHeader(path);
      out.fields = {"x", "y", "z", "intensity"};
      out.encoding = "LAS " + std::to_string(header.version_major) + "." +
                     std::to_string(header.version_minor) + " point format " +
                     std::to_string(header.point_format);
      break;
    }
  }
  return out;
}

}  // namespace hba::io
