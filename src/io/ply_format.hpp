#pragma once
// Internals of the PLY reader: the parsed header.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scalar_type.hpp"

namespace hba::io::detail {

enum class PlyStorage { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  ScalarType type = ScalarType::Float32;  // of the value, or of each list item
  bool is_list = false;
  ScalarType list_count_type = ScalarType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyStorage storage = PlyStorage::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after "end_header\n"
};

// Parses and validates the header at the start of `bytes`. Throws hba::Error
// naming `path`.
PlyHeader parsePlyHeader(std::string_view bytes, const std::filesystem::path& path);

}  // namespace hba::io::detail
