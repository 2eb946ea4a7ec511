// The table of scan formats. A new format: its functions in a file of its
// own, one declaration and one entry here.
#include "hba/io/scan_formats.hpp"

#include "cloud_readers.hpp"
#include "cloud_view.hpp"
#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "text_parsing.hpp"

namespace hba::io {

ScanFormat xyzTextFormat();  // xyz_text.cpp

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

ScanFileFields describePcd(const std::filesystem::path& path) {
  ScanFileFields out;
  const PcdHeader header = readPcdHeader(path);
  for (const PcdField& field : header.fields) {
    out.fields.push_back(field.count == 1 ? field.name
                                          : field.name + "[" + std::to_string(field.count) + "]");
  }
  out.encoding = pcdEncodingName(header.encoding);
  return out;
}

ScanFileFields describeLas(const std::filesystem::path& path) {
  const LasHeader header = readLasHeader(path);
  return {{"x", "y", "z", "intensity"},
          "LAS " + std::to_string(header.version_major) + "." + std::to_string(header.version_minor) +
              " point format " + std::to_string(header.point_format)};
}

ScanFormat pcdFormat() {
  return {".pcd",
          "PCD",
          true,
          [](const std::filesystem::path& p) { return readPcd(p); },
          [](const std::filesystem::path& p, const PointCloud& c) { writePcd(p, c); },
          &detail::readPcdAs<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) {
            detail::writePcdView(p, detail::CloudView(c), PcdEncoding::Binary);
          },
          [](const std::filesystem::path& p) -> std::uint64_t { return readPcdHeader(p).points; },
          &describePcd};
}

ScanFormat kittiBinFormat() {
  return {".bin",
          "KITTI .bin",
          false,
          &readKittiBin,
          &writeKittiBin,
          &detail::readKittiBinAs<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) {
            detail::writeKittiBinView(p, detail::CloudView(c));
          },
          &kittiBinPointCount,
          [](const std::filesystem::path&) {
            return ScanFileFields{{"x", "y", "z", "intensity"}, "KITTI float32"};
          }};
}

ScanFormat plyFormat() {
  return {".ply",
          "PLY",
          true,
          [](const std::filesystem::path& p) { return readPly(p); },
          [](const std::filesystem::path& p, const PointCloud& c) { writePly(p, c); },
          &detail::readPlyAs<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) {
            detail::writePlyView(p, detail::CloudView(c), PlyEncoding::BinaryLittleEndian);
          },
          [](const std::filesystem::path& p) -> std::uint64_t { return readPly(p).size(); },
          [](const std::filesystem::path& p) {
            ScanFileFields out{{"x", "y", "z"}, "PLY"};
            if (readPly(p).hasIntensity()) out.fields.push_back("intensity");
            return out;
          }};
}

ScanFormat lasFormat() {
  return {".las",
          "LAS",
          true,
          [](const std::filesystem::path& p) { return readLas(p); },
          [](const std::filesystem::path& p, const PointCloud& c) { writeLas(p, c); },
          &detail::readLasAs<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) {
            detail::writeLasView(p, detail::CloudView(c), {});
          },
          [](const std::filesystem::path& p) -> std::uint64_t { return readLasHeader(p).point_count; },
          &describeLas};
}

}  // namespace

const std::vector<ScanFormat>& scanFormats() {
  static const std::vector<ScanFormat> formats{pcdFormat(), kittiBinFormat(), plyFormat(), lasFormat(),
                                               xyzTextFormat()};
  return formats;
}

const ScanFormat* findScanFormat(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  for (const ScanFormat& format : scanFormats()) {
    if (detail::equalsIgnoreCase(extension, format.extension)) return &format;
  }
  return nullptr;
}

const ScanFormat& scanFormatOf(const std::filesystem::path& path) {
  if (const ScanFormat* format = findScanFormat(path)) return *format;
  failAt(path, "unknown scan format " + detail::quoteToken(path.extension().string()) + " (hba reads " +
                   scanFormatList() + ")");
}

std::string scanFormatList(bool keeping_doubles) {
  std::vector<std::string> names;
  for (const ScanFormat& format : scanFormats()) {
    if (!keeping_doubles || format.keeps_doubles) names.push_back(format.extension);
  }
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) list += i + 1 == names.size() ? " or " : ", ";
    list += names[i];
  }
  return list;
}

}  // namespace hba::io
