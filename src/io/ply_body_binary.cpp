// PLY binary bodies (either byte order). Fixed-size records are read through
// the shared column loop; records with lists are walked one by one.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "checked_size.hpp"
#include "hba/core/error.hpp"
#include "ply_body.hpp"
#include "point_columns.hpp"
#include "text_parsing.hpp"

namespace hba::io::detail {

namespace {

std::optional<std::size_t> fixedRecordBytes(const PlyElement& element) {
  std::size_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    if (p.is_list) return std::nullopt;
    bytes += scalarSize(p.type);
  }
  return bytes;
}

std::size_t offsetOf(const PlyElement& element, std::size_t property) {
  std::size_t offset = 0;
  for (std::size_t p = 0; p < property; ++p) offset += scalarSize(element.properties[p].type);
  return offset;
}

}  // namespace

void PlyBinaryBody::skipElement(const PlyElement& element) {
  if (const auto record = fixedRecordBytes(element)) {
    advance(checkedMul(element.count, *record, path_, "element size"), element);
    return;
  }
  // Every record holds at least one list count, so this loop ends within the
  // buffer or throws, whatever count the header claims.
  for (std::uint64_t r = 0; r < element.count; ++r) walkRecord(element, nullptr);
}

template <typename Cloud>
Cloud PlyBinaryBody::readVertices(const PlyElement& vertex, const PlyVertexFields& fields) {
  Cloud cloud;
  const bool with_intensity = fields.count == 4;
  if (const auto record = fixedRecordBytes(vertex)) {
    const std::uint64_t total = checkedMul(vertex.count, *record, path_, "vertex data size");
    require(total, vertex);
    const auto column = [&](std::size_t k) {
      const std::size_t p = fields.index[k];
      return Column{bytes_.data() + pos_ + offsetOf(vertex, p), *record, vertex.properties[p].type};
    };
    PointColumns columns{column(0), column(1), column(2), std::nullopt, big_endian_, std::nullopt};
    if (with_intensity) columns.intensity = column(3);
    appendFinitePoints(columns, static_cast<std::size_t>(vertex.count), cloud);
    pos_ += static_cast<std::size_t>(total);
    return cloud;
  }
  cloud.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(vertex.count, remaining())), with_intensity);
  std::vector<std::size_t> starts(vertex.properties.size());  // in the current record
  PointCollector collector(cloud, hasWideCoordinates(vertex, fields), with_intensity);
  for (std::uint64_t r = 0; r < vertex.count; ++r) {
    const std::size_t record_start = pos_;
    walkRecord(vertex, starts.data());
    double values[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < fields.count; ++k) {
      const std::size_t p = fields.index[k];
      values[k] =
          loadAsDouble(bytes_.data() + record_start + starts[p], vertex.properties[p].type, big_endian_);
    }
    collector.add(values);
  }
  collector.finish();
  return cloud;
}

template PointCloud PlyBinaryBody::readVertices(const PlyElement&, const PlyVertexFields&);
template WideCloud PlyBinaryBody::readVertices(const PlyElement&, const PlyVertexFields&);

void PlyBinaryBody::require(std::uint64_t n, const PlyElement& element) const {
  if (n > remaining()) {
    failAt(path_, "truncated: element " + quoteToken(element.name) + " runs past the end of the file");
  }
}

void PlyBinaryBody::advance(std::uint64_t n, const PlyElement& element) {
  require(n, element);
  pos_ += static_cast<std::size_t>(n);
}

std::uint64_t PlyBinaryBody::listCount(const PlyProperty& property, const PlyElement& element) {
  const std::size_t size = scalarSize(property.list_count_type);
  require(size, element);
  const char* p = bytes_.data() + pos_;
  std::int64_t count = 0;
  switch (property.list_count_type) {
    case ScalarType::Int8:
      count = loadUnaligned<std::int8_t>(p, false);
      break;
    case ScalarType::UInt8:
      count = loadUnaligned<std::uint8_t>(p, false);
      break;
    case ScalarType::Int16:
      count = loadUnaligned<std::int16_t>(p, big_endian_);
      break;
    case ScalarType::UInt16:
      count = loadUnaligned<std::uint16_t>(p, big_endian_);
      break;
    case ScalarType::Int32:
      count = loadUnaligned<std::int32_t>(p, big_endian_);
      break;
    default:
      count = loadUnaligned<std::uint32_t>(p, big_endian_);
      break;
  }
  if (count < 0) failAt(path_, "element " + quoteToken(element.name) + " has a negative list length");
  pos_ += size;
  return static_cast<std::uint64_t>(count);
}

// Moves past one record; when `starts` is given, stores where each property begins.
void PlyBinaryBody::walkRecord(const PlyElement& element, std::size_t* starts) {
  const std::size_t record_start = pos_;
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    if (starts) starts[p] = pos_ - record_start;
    const std::uint64_t items = property.is_list ? listCount(property, element) : 1;
    advance(checkedMul(items, scalarSize(property.type), path_, "list size"), element);
  }
}

}  // namespace hba::io::detail
