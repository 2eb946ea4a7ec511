// PLY header parsing: "ply", one "format" line, then elements and their
// properties (comment and obj_info lines skipped) up to "end_header".
#include <string>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"
#include "ply_format.hpp"
#include "text_parsing.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// A header longer than this is not a PLY header.
constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

ScalarType plyScalarType(std::string_view word, const fs::path& path) {
  struct Name {
    const char* name;
    ScalarType type;
  };
  // Both the original names and the sized aliases of later writers.
  static const Name kNames[] = {
      {"char", ScalarType::Int8},      {"int8", ScalarType::Int8},       {"uchar", ScalarType::UInt8},
      {"uint8", ScalarType::UInt8},    {"short", ScalarType::Int16},     {"int16", ScalarType::Int16},
      {"ushort", ScalarType::UInt16},  {"uint16", ScalarType::UInt16},   {"int", ScalarType::Int32},
      {"int32", ScalarType::Int32},    {"uint", ScalarType::UInt32},     {"uint32", ScalarType::UInt32},
      {"float", ScalarType::Float32},  {"float32", ScalarType::Float32}, {"double", ScalarType::Float64},
      {"float64", ScalarType::Float64}};
  for (const Name& name : kNames) {
    if (word == name.name) return name.type;
  }
  failAt(path, "unknown PLY property type " + quoteToken(word));
}

PlyStorage parseFormat(std::string_view rest, const fs::path& path) {
  const std::string_view storage = nextWord(rest);
  const std::string_view version = nextWord(rest);
  if (version != "1.0") failAt(path, "unsupported PLY version " + quoteToken(version));
  if (storage == "ascii") return PlyStorage::Ascii;
  if (storage == "binary_little_endian") return PlyStorage::BinaryLittleEndian;
  if (storage == "binary_big_endian") return PlyStorage::BinaryBigEndian;
  failAt(path, "unknown PLY format " + quoteToken(storage));
}

PlyElement parseElement(std::string_view rest, const fs::path& path) {
  PlyElement element;
  element.name = std::string(nextWord(rest));
  const std::string_view count = nextWord(rest);
  if (element.name.empty() || count.empty()) failAt(path, "an element line needs a name and a count");
  if (count.front() == '-') {
    failAt(path, "element " + quoteToken(element.name) + " has a negative count");
  }
  const std::optional<std::uint64_t> number = parseUnsigned(count);
  if (!number) {
    failAt(path, "element " + quoteToken(element.name) + " has an invalid count " + quoteToken(count));
  }
  element.count = *number;
  return element;
}

PlyProperty parseProperty(std::string_view rest, const fs::path& path) {
  PlyProperty property;
  std::string_view type = nextWord(rest);
  if (type == "list") {
    property.is_list = true;
    property.list_count_type = plyScalarType(nextWord(rest), path);
    if (property.list_count_type == ScalarType::Float32 || property.list_count_type == ScalarType::Float64) {
      failAt(path, "a list count must have an integer type");
    }
    type = nextWord(rest);
  }
  property.type = plyScalarType(type, path);
  property.name = std::string(nextWord(rest));
  if (property.name.empty()) failAt(path, "a property line has no name");
  return property;
}

}  // namespace

PlyHeader parsePlyHeader(std::string_view bytes, const fs::path& path) {
  if (bytes.empty()) failAt(path, "empty file");
  std::string_view rest = bytes.substr(0, kMaxPlyHeaderBytes);
  const std::size_t window = rest.size();
  rest = withoutByteOrderMark(rest);  // an ascii PLY saved by a Windows editor
  std::string_view first = nextLine(rest);
  if (nextWord(first) != "ply") failAt(path, "not a PLY file (it does not start with \"ply\")");

  PlyHeader header;
  bool has_format = false;
  while (!rest.empty()) {
    std::string_view words = nextLine(rest);
    const std::string_view key = nextWord(words);
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (has_format) failAt(path, "the PLY header has two format lines");
      header.storage = parseFormat(words, path);
      has_format = true;
    } else if (key == "element") {
      header.elements.push_back(parseElement(words, path));
    } else if (key == "property") {
      if (header.elements.empty()) failAt(path, "a PLY property comes before any element");
      header.elements.back().properties.push_back(parseProperty(words, path));
    } else if (key == "end_header") {
      if (!has_format) failAt(path, "the PLY header has no format line");
      header.data_offset = window - rest.size();
      return header;
    } else {
      failAt(path, "unexpected PLY header line starting with " + quoteToken(key));
    }
  }
  failAt(path, "the PLY header has no end_header line (truncated?)");
}

}  // namespace hba::io::detail
