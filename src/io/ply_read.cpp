// readPly: the vertex element's x y z (and intensity) from ascii or binary
// bodies. Elements before the vertices are skipped record by record (their
// lists sized as declared); elements after them are never touched.
#include <algorithm>
#include <string>

#include "checked_size.hpp"
#include "file_bytes.hpp"
#include "hba/core/error.hpp"
#include "hba/io/ply.hpp"
#include "ply_format.hpp"
#include "point_columns.hpp"
#include "text_numbers.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using detail::PlyElement;
using detail::PlyProperty;
using detail::ScalarType;

// Property indices of the values hba keeps, in the order x y z intensity.
struct VertexFields {
  std::size_t index[4] = {0, 0, 0, 0};
  std::size_t count = 3;  // 4 with intensity
};

// CloudCompare names its scalar fields "scalar_<name>".
bool isIntensityName(std::string_view name) {
  return detail::equalsIgnoreCase(name, "intensity") ||
         detail::equalsIgnoreCase(name, "scalar_intensity");
}

VertexFields findVertexFields(const PlyElement& vertex, const fs::path& path) {
  std::optional<std::size_t> found[4];
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    const std::string& name = vertex.properties[p].name;
    const int slot = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : isIntensityName(name) ? 3 : -1;
    if (slot < 0) continue;
    if (found[slot]) failAt(path, "vertex property " + detail::quoteToken(name) + " appears twice");
    if (vertex.properties[p].is_list) {
      failAt(path, "vertex property " + detail::quoteToken(name) + " is a list");
    }
    found[slot] = p;
  }
  if (!found[0] || !found[1] || !found[2]) failAt(path, "the vertices have no x, y and z");
  VertexFields fields;
  fields.count = found[3] ? 4 : 3;
  for (std::size_t k = 0; k < fields.count; ++k) fields.index[k] = *found[k];
  return fields;
}

void addPoint(const float (&values)[4], bool with_intensity, PointCloud& cloud) {
  const Vec3f p(values[0], values[1], values[2]);
  if (!p.allFinite()) return;
  if (with_intensity) {
    cloud.add(p, values[3]);
  } else {
    cloud.add(p);
  }
}

// ---- binary ----------------------------------------------------------------

class BinaryBody {
 public:
  BinaryBody(std::string_view bytes, bool big_endian, const fs::path& path)
      : bytes_(bytes), big_endian_(big_endian), path_(path) {}

  void skipElement(const PlyElement& element) {
    if (const auto record = fixedRecordBytes(element)) {
      advance(detail::checkedMul(element.count, *record, path_, "element size"), element);
      return;
    }
    // Every record holds at least one list count, so this loop ends within
    // the buffer or throws.
    for (std::uint64_t r = 0; r < element.count; ++r) walkRecord(element, nullptr);
  }

  PointCloud readVertices(const PlyElement& vertex, const VertexFields& fields) {
    PointCloud cloud;
    if (const auto record = fixedRecordBytes(vertex)) {
      const std::uint64_t total = detail::checkedMul(vertex.count, *record, path_, "vertex data size");
      require(total, vertex);
      const auto column = [&](std::size_t k) {
        const std::size_t p = fields.index[k];
        return detail::Column{bytes_.data() + pos_ + offsetOf(vertex, p), *record,
                              vertex.properties[p].type};
      };
      detail::PointColumns columns{column(0), column(1), column(2), std::nullopt, big_endian_};
      if (fields.count == 4) columns.intensity = column(3);
      detail::appendFinitePoints(columns, static_cast<std::size_t>(vertex.count), cloud);
      pos_ += static_cast<std::size_t>(total);
      return cloud;
    }
    cloud.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(vertex.count, remaining())),
                  fields.count == 4);
    std::vector<std::size_t> starts(vertex.properties.size());  // in the current record
    for (std::uint64_t r = 0; r < vertex.count; ++r) {
      const std::size_t record_start = pos_;
      walkRecord(vertex, starts.data());
      float values[4] = {0, 0, 0, 0};
      for (std::size_t k = 0; k < fields.count; ++k) {
        const std::size_t p = fields.index[k];
        values[k] = detail::loadAsFloat(bytes_.data() + record_start + starts[p],
                                        vertex.properties[p].type, big_endian_);
      }
      addPoint(values, fields.count == 4, cloud);
    }
    return cloud;
  }

 private:
  static std::optional<std::size_t> fixedRecordBytes(const PlyElement& element) {
    std::size_t bytes = 0;
    for (const PlyProperty& p : element.properties) {
      if (p.is_list) return std::nullopt;
      bytes += detail::scalarSize(p.type);
    }
    return bytes;
  }

  static std::size_t offsetOf(const PlyElement& element, std::size_t property) {
    std::size_t offset = 0;
    for (std::size_t p = 0; p < property; ++p) offset += detail::scalarSize(element.properties[p].type);
    return offset;
  }

  std::uint64_t remaining() const { return bytes_.size() - pos_; }

  void require(std::uint64_t n, const PlyElement& element) const {
    if (n > remaining()) {
      failAt(path_, "truncated: element " + detail::quoteToken(element.name) +
                        " runs past the end of the file");
    }
  }

  void advance(std::uint64_t n, const PlyElement& element) {
    require(n, element);
    pos_ += static_cast<std::size_t>(n);
  }

  std::uint64_t listCount(const PlyProperty& property, const PlyElement& element) {
    const std::size_t size = detail::scalarSize(property.list_count_type);
    require(size, element);
    const char* p = bytes_.data() + pos_;
    std::int64_t count = 0;
    switch (property.list_count_type) {
      case ScalarType::Int8: count = detail::loadUnaligned<std::int8_t>(p, false); break;
      case ScalarType::UInt8: count = detail::loadUnaligned<std::uint8_t>(p, false); break;
      case ScalarType::Int16: count = detail::loadUnaligned<std::int16_t>(p, big_endian_); break;
      case ScalarType::UInt16: count = detail::loadUnaligned<std::uint16_t>(p, big_endian_); break;
      case ScalarType::Int32: count = detail::loadUnaligned<std::int32_t>(p, big_endian_); break;
      default: count = detail::loadUnaligned<std::uint32_t>(p, big_endian_); break;
    }
    if (count < 0) failAt(path_, "element " + detail::quoteToken(element.name) + " has a negative list length");
    pos_ += size;
    return static_cast<std::uint64_t>(count);
  }

  // Moves past one record; when `starts` is given, stores where each property begins.
  void walkRecord(const PlyElement& element, std::size_t* starts) {
    const std::size_t record_start = pos_;
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      if (starts) starts[p] = pos_ - record_start;
      const std::uint64_t items = property.is_list ? listCount(property, element) : 1;
      advance(detail::checkedMul(items, detail::scalarSize(property.type), path_, "list size"), element);
    }
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
  bool big_endian_;
  const fs::path& path_;
};

// ---- ascii -----------------------------------------------------------------

class AsciiBody {
 public:
  AsciiBody(std::string_view text, const fs::path& path) : rest_(text), path_(path) {}

  void skipElement(const PlyElement& element) {
    if (element.properties.empty()) return;  // nothing to read, however many records
    for (std::uint64_t r = 0; r < element.count; ++r) {
      for (const PlyProperty& property : element.properties) skipProperty(property, element);
    }
  }

  PointCloud readVertices(const PlyElement& vertex, const VertexFields& fields) {
    PointCloud cloud;
    // Every value takes at least two characters, which bounds a lying count.
    const std::uint64_t most_possible = rest_.size() / (2 * vertex.properties.size()) + 1;
    cloud.reserve(static_cast<std::size_t>(std::min(vertex.count, most_possible)), fields.count == 4);
    for (std::uint64_t r = 0; r < vertex.count; ++r) {
      float values[4] = {0, 0, 0, 0};
      for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
        const PlyProperty& property = vertex.properties[p];
        if (property.is_list) {
          skipProperty(property, vertex);
          continue;
        }
        const std::string_view word = token(vertex);
        for (std::size_t k = 0; k < fields.count; ++k) {
          if (fields.index[k] == p) values[k] = parseValue(word, property.type, r);
        }
      }
      addPoint(values, fields.count == 4, cloud);
    }
    return cloud;
  }

 private:
  std::string_view token(const PlyElement& element) {
    const std::string_view word = detail::nextToken(rest_);
    if (word.empty()) {
      failAt(path_, "truncated: element " + detail::quoteToken(element.name) + " ends early");
    }
    return word;
  }

  void skipProperty(const PlyProperty& property, const PlyElement& element) {
    const std::string_view first = token(element);
    if (!property.is_list) return;
    const std::optional<std::uint64_t> items = detail::parseUnsigned(first);
    if (!items) failAt(path_, "bad list length " + detail::quoteToken(first));
    for (std::uint64_t i = 0; i < *items; ++i) token(element);
  }

  // float32 text is parsed as float directly: through double it could round twice.
  float parseValue(std::string_view word, ScalarType type, std::uint64_t vertex) const {
    std::optional<float> value;
    if (type == ScalarType::Float32) {
      value = detail::parseFloat(word);
    } else if (const std::optional<double> wide = detail::parseDouble(word)) {
      value = static_cast<float>(*wide);
    }
    if (!value) {
      failAt(path_, "vertex " + std::to_string(vertex) + ": " + detail::quoteToken(word) +
                        " is not a number");
    }
    return *value;
  }

  std::string_view rest_;
  const fs::path& path_;
};

template <typename Body>
PointCloud readVertexElement(Body body, const detail::PlyHeader& header, const fs::path& path) {
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") return body.readVertices(element, findVertexFields(element, path));
    body.skipElement(element);
  }
  failAt(path, "the PLY file has no vertex element");
}

}  // namespace

PointCloud readPly(const fs::path& path) {
  const detail::FileBytes bytes = detail::readFileBytes(path);
  const detail::PlyHeader header = detail::parsePlyHeader(bytes.view(), path);
  const std::string_view body = bytes.view().substr(header.data_offset);
  if (header.storage == detail::PlyStorage::Ascii) {
    return readVertexElement(AsciiBody(body, path), header, path);
  }
  const bool big_endian = header.storage == detail::PlyStorage::BinaryBigEndian;
  return readVertexElement(BinaryBody(body, big_endian, path), header, path);
}

}  // namespace hba::io
