#pragma once
// What a scan file holds, read as cheaply as its format allows (a PCD's
// or LAS header, a .bin's size; a PLY is read whole): for `hba info`.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace hba::io {

// Points stored in the file (NaN points included). Throws hba::Error.
std::uint64_t storedPointCount(const std::filesystem::path& path);

struct ScanFileFields {
  std::vector<std::string> fields;  // "x", "y", "z", "intensity", "rgb[4]" ...
  std::string encoding;             // "PCD binary", "KITTI float32", "PLY" ...
};

// The fields a scan file stores and their encoding. Throws hba::Error.
ScanFileFields describeScanFields(const std::filesystem::path& path);

}  // namespace hba::io
