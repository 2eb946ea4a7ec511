// PLY ascii bodies: a stream of words, records in header order.
#include <algorithm>
#include <string>

#include "hba/core/error.hpp"
#include "ply_body.hpp"
#include "text_parsing.hpp"

namespace hba::io::detail {

bool hasWideCoordinates(const PlyElement& vertex, const PlyVertexFields& fields) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (vertex.properties[fields.index[k]].type == ScalarType::Float64) return true;
  }
  return false;
}

void PlyAsciiBody::skipElement(const PlyElement& element) {
  if (element.properties.empty()) return;  // nothing to read, however many records
  // Each record takes at least one word, so a lying count runs out of words
  // (and throws) instead of looping on.
  for (std::uint64_t r = 0; r < element.count; ++r) {
    for (const PlyProperty& property : element.properties) skipProperty(property, element);
  }
}

template <typename Cloud>
Cloud PlyAsciiBody::readVertices(const PlyElement& vertex, const PlyVertexFields& fields) {
  Cloud cloud;
  const bool with_intensity = fields.count == 4;
  // Every value takes at least two characters, which bounds a lying count.
  const std::uint64_t most_possible = rest_.size() / (2 * vertex.properties.size()) + 1;
  cloud.reserve(static_cast<std::size_t>(std::min(vertex.count, most_possible)), with_intensity);
  PointCollector collector(cloud, hasWideCoordinates(vertex, fields), with_intensity);
  for (std::uint64_t r = 0; r < vertex.count; ++r) {
    double values[4] = {0, 0, 0, 0};
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
    collector.add(values);
  }
  collector.finish();
  return cloud;
}

template PointCloud PlyAsciiBody::readVertices(const PlyElement&, const PlyVertexFields&);
template WideCloud PlyAsciiBody::readVertices(const PlyElement&, const PlyVertexFields&);

std::string_view PlyAsciiBody::token(const PlyElement& element) {
  const std::string_view word = nextToken(rest_);
  if (word.empty()) failAt(path_, "truncated: element " + quoteToken(element.name) + " ends early");
  return word;
}

void PlyAsciiBody::skipProperty(const PlyProperty& property, const PlyElement& element) {
  const std::string_view first = token(element);
  if (!property.is_list) return;
  const std::optional<std::uint64_t> items = parseUnsigned(first);
  if (!items) failAt(path_, "bad list length " + quoteToken(first));
  for (std::uint64_t i = 0; i < *items; ++i) token(element);
}

// float32 text is parsed as float directly: through double it could round twice.
double PlyAsciiBody::parseValue(std::string_view word, ScalarType type, std::uint64_t vertex) const {
  std::optional<double> value;
  if (type == ScalarType::Float32) {
    if (const std::optional<float> narrow = parseFloat(word)) value = *narrow;
  } else if (const std::optional<double> wide = parseDouble(word)) {
    // Integers and float64 as float64 text would give them, then rounded once.
    value = type == ScalarType::Float64 ? *wide : static_cast<double>(static_cast<float>(*wide));
  }
  if (!value) {
    failAt(path_, "vertex " + std::to_string(vertex) + ": " + quoteToken(word) + " is not a number");
  }
  return *value;
}

}  // namespace hba::io::detail
