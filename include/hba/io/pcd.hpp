#pragma once
// PCD (Point Cloud Library format) reading and writing.
// Reads ascii, binary and binary_compressed (LZF) files with fields x y z
// (required) and intensity (optional); every other field is skipped by its
// declared SIZE/TYPE/COUNT. NaN/Inf points are dropped.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

enum class PcdEncoding { Ascii, Binary, BinaryCompressed };

struct PcdField {
  std::string name;
  int size = 4;     // bytes per element
  char type = 'F';  // F float, I signed, U unsigned
  int count = 1;    // elements
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 1;
  std::uint64_t points = 0;
  PcdEncoding encoding = PcdEncoding::Binary;
  std::size_t data_offset = 0;  // byte offset of the first data byte
};

// Parses only the header (cheap: used by `hba info`). Throws hba::Error.
PcdHeader readPcdHeader(const std::filesystem::path& path);
PointCloud readPcd(const std::filesystem::path& path);
void writePcd(const std::filesystem::path& path, const PointCloud& cloud,
              PcdEncoding encoding = PcdEncoding::Binary);

}  // namespace hba::io
