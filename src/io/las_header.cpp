// The LAS public header: each field hba relies on is checked before a single
// point is read, so a lying or truncated header fails with a message.
#include "las_header.hpp"

#include <cmath>
#include <string>
#include <system_error>

#include "checked_size.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "io/file_warnings.hpp"
#include "las_format.hpp"

namespace hba::io::detail {
namespace {

std::size_t minimumHeaderSize(int minor) {
  if (minor <= 2) return kLasHeaderSize12;
  return minor == 3 ? kLasHeaderSize13 : kLasHeaderSize14;
}

Vec3 loadVec3(const char* at) {
  return {loadLittleEndian<double>(at), loadLittleEndian<double>(at + 8), loadLittleEndian<double>(at + 16)};
}

std::string textField(const char* at) {
  std::string text(at, kLasTextFieldBytes);
  const std::size_t end = text.find('\0');
  return end == std::string::npos ? text : text.substr(0, end);
}

void checkVersion(const LasHeader& header, const std::filesystem::path& path) {
  if (header.version_major != 1 || header.version_minor > 4) {
    failAt(path, "LAS version " + std::to_string(header.version_major) + "." +
                     std::to_string(header.version_minor) + " is not supported (hba reads 1.0 to 1.4)");
  }
}

void checkPointFormat(const LasHeader& header, std::uint8_t format_byte, const std::filesystem::path& path) {
  if (format_byte & kLasCompressedBits) {
    failAt(path, "is LAZ-compressed (point format byte " + std::to_string(format_byte) +
                     "); hba reads uncompressed LAS only: decompress it first (e.g. laszip)");
  }
  if (header.point_format > kLasMaxPointFormat) {
    failAt(path, "unknown point data record format " + std::to_string(header.point_format) +
                     " (LAS defines 0 to 10)");
  }
  if (header.point_format > 5 && header.version_minor < 4) {
    failAt(path, "point data record format " + std::to_string(header.point_format) + " needs LAS 1.4, but " +
                     "the header says 1." + std::to_string(header.version_minor));
  }
  const std::uint16_t minimum = kLasMinRecordLength[header.point_format];
  if (header.record_length < minimum) {
    failAt(path, "point record length " + std::to_string(header.record_length) + " is shorter than the " +
                     std::to_string(minimum) + " bytes of point data record format " +
                     std::to_string(header.point_format));
  }
}

void checkScaleAndOffset(const LasHeader& header, const std::filesystem::path& path) {
  const char axes[] = "xyz";
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(header.scale[a]) || header.scale[a] == 0.0) {
      failAt(path, std::string("the ") + axes[a] + " scale factor " + std::to_string(header.scale[a]) +
                       " is not a finite, non-zero number");
    }
    if (!std::isfinite(header.offset[a])) {
      failAt(path, std::string("the ") + axes[a] + " offset is not a finite number");
    }
  }
}

// 1.4 has a 64-bit count; the legacy 32-bit one may be zero (formats 6-10
// must leave it zero) but, when both are set, they must agree.
std::uint64_t declaredPointCount(const char* data, const LasHeader& header,
                                 const std::filesystem::path& path) {
  if (header.version_minor < 4) return header.legacy_point_count;
  const auto count = loadLittleEndian<std::uint64_t>(data + las_field::kPointCount);
  if (count == 0) return header.legacy_point_count;
  if (header.legacy_point_count != 0 && header.legacy_point_count != count) {
    failAt(path, "the legacy point count " + std::to_string(header.legacy_point_count) +
                     " contradicts the 64-bit point count " + std::to_string(count));
  }
  return count;
}

// Where the point records end at the latest: the file's end, or the
// waveform data (1.3) or extended VLRs (1.4) stored after them.
std::uint64_t pointDataLimit(const char* data, const LasHeader& header, std::uint64_t file_size) {
  std::uint64_t limit = file_size;
  const auto lower = [&](std::uint64_t start) {
    if (start > header.point_data_offset && start < limit) limit = start;
  };
  if (header.version_minor >= 3) lower(loadLittleEndian<std::uint64_t>(data + las_field::kWaveformStart));
  if (header.version_minor >= 4 && loadLittleEndian<std::uint32_t>(data + las_field::kEvlrCount) > 0) {
    lower(loadLittleEndian<std::uint64_t>(data + las_field::kFirstEvlrStart));
  }
  return limit;
}

// Some writers leave every count at 0 and still store the records: read
// those that fit, with a warning, rather than an empty scan without a word.
std::uint64_t pointCount(const char* data, const LasHeader& header, std::uint64_t file_size,
                         const std::filesystem::path& path) {
  const std::uint64_t declared = declaredPointCount(data, header, path);
  const std::uint64_t limit = pointDataLimit(data, header, file_size);
  // (An offset inside the header fails checkLayout.)
  if (declared != 0 || header.point_data_offset < header.header_size || limit <= header.point_data_offset) {
    return declared;
  }
  const std::uint64_t bytes = limit - header.point_data_offset;
  const std::uint64_t records = bytes / header.record_length;
  if (records == 0) return 0;
  const std::uint64_t left_over = bytes % header.record_length;
  warnAboutFile(path, "LAS point count 0 before point records",
                "the header counts 0 points, but " + std::to_string(bytes) +
                    " bytes of point records follow it: " + "reading the " + std::to_string(records) +
                    " records of " + std::to_string(header.record_length) + " bytes they hold" +
                    (left_over ? " (" + std::to_string(left_over) + " bytes left over)" : std::string()));
  return records;
}

void checkLayout(const LasHeader& header, std::uint64_t file_size, const std::filesystem::path& path) {
  if (header.header_size < minimumHeaderSize(header.version_minor)) {
    failAt(path, "header size " + std::to_string(header.header_size) + " is below the " +
                     std::to_string(minimumHeaderSize(header.version_minor)) + " bytes of a LAS 1." +
                     std::to_string(header.version_minor) + " header");
  }
  if (header.point_data_offset < header.header_size) {
    failAt(path, "the point data offset " + std::to_string(header.point_data_offset) +
                     " lies inside the header (" + std::to_string(header.header_size) + " bytes)");
  }
  const std::uint64_t point_bytes =
      checkedMul(header.point_count, header.record_length, path, "point data size");
  const std::uint64_t end = checkedAdd(header.point_data_offset, point_bytes, path, "point data end");
  if (end > file_size) {
    failAt(path, "truncated: the header declares " + std::to_string(header.point_count) + " points of " +
                     std::to_string(header.record_length) + " bytes from byte " +
                     std::to_string(header.point_data_offset) + " (to byte " + std::to_string(end) +
                     ") but the file has " + std::to_string(file_size) + " bytes");
  }
}

}  // namespace

LasHeader parseLasHeader(const char* data, std::size_t available, std::uint64_t file_size,
                         const std::filesystem::path& path) {
  if (file_size == 0) failAt(path, "empty file");
  if (available < 4 || std::string(data, 4) != "LASF") failAt(path, "not a LAS file (no LASF signature)");
  if (available < kLasHeaderSize12) {
    failAt(path, "truncated: " + std::to_string(available) + " bytes are too few for a LAS header (" +
                     std::to_string(kLasHeaderSize12) + ")");
  }
  LasHeader header;
  header.version_major = static_cast<std::uint8_t>(data[las_field::kVersionMajor]);
  header.version_minor = static_cast<std::uint8_t>(data[las_field::kVersionMinor]);
  checkVersion(header, path);
  const std::size_t needed = minimumHeaderSize(header.version_minor);
  if (available < needed) {
    failAt(path, "truncated: " + std::to_string(available) + " bytes are too few for a LAS 1." +
                     std::to_string(header.version_minor) + " header (" + std::to_string(needed) + ")");
  }
  header.generating_software = textField(data + las_field::kGeneratingSoftware);
  header.header_size = loadLittleEndian<std::uint16_t>(data + las_field::kHeaderSize);
  header.point_data_offset = loadLittleEndian<std::uint32_t>(data + las_field::kPointDataOffset);
  header.vlr_count = loadLittleEndian<std::uint32_t>(data + las_field::kVlrCount);
  const auto format_byte = static_cast<std::uint8_t>(data[las_field::kPointFormat]);
  header.point_format = format_byte & ~kLasCompressedBits;
  header.record_length = loadLittleEndian<std::uint16_t>(data + las_field::kRecordLength);
  header.legacy_point_count = loadLittleEndian<std::uint32_t>(data + las_field::kLegacyPointCount);
  header.scale = loadVec3(data + las_field::kScale);
  header.offset = loadVec3(data + las_field::kOffset);
  for (int a = 0; a < 3; ++a) {
    header.max[a] = loadLittleEndian<double>(data + las_field::kBounds + 16 * a);
    header.min[a] = loadLittleEndian<double>(data + las_field::kBounds + 16 * a + 8);
  }
  checkPointFormat(header, format_byte, path);
  checkScaleAndOffset(header, path);
  header.point_count = pointCount(data, header, file_size, path);
  checkLayout(header, file_size, path);
  return header;
}

}  // namespace hba::io::detail

namespace hba::io {

LasHeader readLasHeader(const std::filesystem::path& path) {
  const detail::FileBytes head = detail::readFileHead(path, detail::kLasHeaderSize14);
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) failAt(path, "cannot read the file size: " + ec.message());
  return detail::parseLasHeader(head.data(), head.size(), file_size, path);
}

}  // namespace hba::io
