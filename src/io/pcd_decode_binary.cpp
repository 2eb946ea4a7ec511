// PCD "DATA binary" (row-major records) and "DATA binary_compressed" (an LZF
// block holding all values of field 1, then all of field 2, ...).
#include <string>

#include "checked_size.hpp"
#include "hba/core/error.hpp"
#include "lzf_block.hpp"
#include "pcd_format.hpp"
#include "point_columns.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// The columns of x, y, z (and intensity) given where a field's values start
// and the distance between consecutive ones.
template <typename FirstOf, typename StrideOf>
PointColumns pcdColumns(const PcdHeader& header, const PcdLayout& layout, FirstOf first_of,
                        StrideOf stride_of) {
  const auto column = [&](std::size_t field) {
    return Column{first_of(field), stride_of(field), pcdScalarType(header.fields[field])};
  };
  PointColumns columns{column(layout.x), column(layout.y), column(layout.z), std::nullopt, false,
                       std::nullopt};
  if (layout.intensity) columns.intensity = column(*layout.intensity);
  if (layout.time) columns.time = column(*layout.time);
  return columns;
}

std::string describeSize(const PcdHeader& header, const PcdLayout& layout) {
  return std::to_string(header.points) + " points of " + std::to_string(layout.point_bytes) + " bytes";
}

std::uint32_t loadUint32(const char* p) { return loadUnaligned<std::uint32_t>(p, false); }

}  // namespace

template <typename Cloud>
Cloud decodePcdBinary(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                      const fs::path& path) {
  const std::uint64_t needed = checkedMul(header.points, layout.point_bytes, path, "data size");
  if (needed > body.size()) {
    failAt(path, "truncated: the header declares " + describeSize(header, layout) + " (" +
                     std::to_string(needed) + " bytes) but only " + std::to_string(body.size()) +
                     " bytes follow it");
  }
  const PointColumns columns = pcdColumns(
      header, layout, [&](std::size_t f) { return body.data() + layout.byte_offsets[f]; },
      [&](std::size_t) { return layout.point_bytes; });
  Cloud cloud;
  appendFinitePoints(columns, static_cast<std::size_t>(header.points), cloud);
  return cloud;
}

template <typename Cloud>
Cloud decodePcdCompressed(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                          const fs::path& path) {
  const std::uint64_t expected = checkedMul(header.points, layout.point_bytes, path, "data size");
  if (expected == 0 && body.size() < 8) return {};  // some writers omit the sizes of nothing
  if (body.size() < 8) failAt(path, "truncated: the compressed block sizes are missing");
  const std::uint32_t compressed_size = loadUint32(body.data());
  const std::uint32_t raw_size = loadUint32(body.data() + 4);
  if (raw_size != expected) {
    failAt(path, "the compressed block inflates to " + std::to_string(raw_size) +
                     " bytes but the header declares " + describeSize(header, layout) + " (" +
                     std::to_string(expected) + " bytes)");
  }
  if (compressed_size > body.size() - 8) {
    failAt(path, "truncated: the compressed block should have " + std::to_string(compressed_size) +
                     " bytes but only " + std::to_string(body.size() - 8) + " follow");
  }
  if (expected == 0) return {};
  const std::unique_ptr<char[]> raw = lzfDecompress(body.substr(8, compressed_size), raw_size, path);
  // Field f's values start after every earlier field's values for all points.
  const std::size_t n = static_cast<std::size_t>(header.points);
  const PointColumns columns = pcdColumns(
      header, layout, [&](std::size_t f) { return raw.get() + n * layout.byte_offsets[f]; },
      [&](std::size_t f) { return static_cast<std::size_t>(header.fields[f].size); });
  Cloud cloud;
  appendFinitePoints(columns, n, cloud);
  return cloud;
}

template PointCloud decodePcdBinary(std::string_view, const PcdHeader&, const PcdLayout&, const fs::path&);
template WideCloud decodePcdBinary(std::string_view, const PcdHeader&, const PcdLayout&, const fs::path&);
template PointCloud decodePcdCompressed(std::string_view, const PcdHeader&, const PcdLayout&,
                                        const fs::path&);
template WideCloud decodePcdCompressed(std::string_view, const PcdHeader&, const PcdLayout&, const fs::path&);

}  // namespace hba::io::detail
