// readLas: every point format stores x y z as scaled int32 at bytes 0-11 and
// intensity as uint16 at byte 12, so one loop serves formats 0 to 10; the
// rest of each record is skipped by the declared record length.
#include <cstdint>
#include <string>

#include "cloud_readers.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "hba/io/las.hpp"
#include "las_format.hpp"
#include "las_header.hpp"
#include "point_columns.hpp"

namespace hba::io {
namespace {

// The variable length records sit between the header and the points; a
// count or a length that runs past the point data betrays a corrupt header.
void checkVlrsFit(const detail::FileBytes& bytes, const LasHeader& header,
                  const std::filesystem::path& path) {
  std::uint64_t at = header.header_size;
  for (std::uint32_t i = 0; i < header.vlr_count; ++i) {
    if (at + detail::kLasVlrHeaderSize > header.point_data_offset) {
      failAt(path, "variable length record " + std::to_string(i + 1) + " of " +
                       std::to_string(header.vlr_count) + " does not fit before the point data (byte " +
                       std::to_string(header.point_data_offset) + ")");
    }
    const auto length =
        detail::loadLittleEndian<std::uint16_t>(bytes.data() + at + detail::kLasVlrLengthField);
    at += detail::kLasVlrHeaderSize + length;
  }
  if (at > header.point_data_offset) {
    failAt(path, "the variable length records end at byte " + std::to_string(at) +
                     ", past the point data offset " + std::to_string(header.point_data_offset));
  }
}

}  // namespace

namespace detail {

template <typename Cloud>
Cloud readLasAs(const std::filesystem::path& path) {
  const FileBytes bytes = readFileBytes(path);
  const LasHeader header = parseLasHeader(bytes.data(), bytes.size(), bytes.size(), path);
  checkVlrsFit(bytes, header, path);
  Cloud cloud;
  // LAS coordinates are wide (scaled int32 plus a double offset): the
  // collector gives far-out clouds an origin instead of rounding them to floats.
  PointCollector collector(cloud, true, true);
  const char* record = bytes.data() + header.point_data_offset;
  for (std::uint64_t i = 0; i < header.point_count; ++i, record += header.record_length) {
    double values[4];
    for (int a = 0; a < 3; ++a) {
      values[a] =
          loadLittleEndian<std::int32_t>(record + las_point::kX + 4 * a) * header.scale[a] + header.offset[a];
    }
    values[3] = loadLittleEndian<std::uint16_t>(record + las_point::kIntensity);
    collector.add(values);
  }
  collector.finish();
  return cloud;
}

template PointCloud readLasAs(const std::filesystem::path&);
template WideCloud readLasAs(const std::filesystem::path&);

}  // namespace detail

PointCloud readLas(const std::filesystem::path& path) { return detail::readLasAs<PointCloud>(path); }

}  // namespace hba::io
