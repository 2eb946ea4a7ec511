#pragma once
// Internals of the PCD reader and writer shared by its source files.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/wide_cloud.hpp"
#include "scalar_type.hpp"

namespace hba::io::detail {

// A PCD header longer than this is not a PCD header.
constexpr std::size_t kMaxPcdHeaderBytes = 64 * 1024;

// Parses the header at the start of `bytes` and validates it on its own terms
// (types, sizes, counts, WIDTH x HEIGHT = POINTS). Returns nullopt when the
// DATA line is not yet complete and `is_whole_file` is false, so the caller
// can read more. Throws hba::Error naming `path` for any bad header.
std::optional<PcdHeader> parsePcdHeader(std::string_view bytes, bool is_whole_file,
                                        const std::filesystem::path& path);

// The error for a file whose first kMaxPcdHeaderBytes hold no complete header.
[[noreturn]] void failNoPcdDataLine(const std::filesystem::path& path);

ScalarType pcdScalarType(const PcdField& field);  // of a validated field

// Where the fields hba reads sit in one point.
struct PcdLayout {
  std::vector<std::size_t> byte_offsets;  // of each field in a row-major record
  std::vector<std::size_t> first_words;   // index of each field's first word on an ascii line
  std::size_t point_bytes = 0;
  std::size_t words_per_point = 0;
  std::size_t x = 0, y = 0, z = 0;  // field indices
  std::optional<std::size_t> intensity;
  std::optional<std::size_t> time;  // a raw sweep's per-point time (t, time, timestamp, offset_time)
};

// Requires x, y and z (COUNT 1, each named once); intensity is optional.
PcdLayout pcdLayout(const PcdHeader& header, const std::filesystem::path& path);

// Decoders of the bytes after the header; every one checks the declared sizes
// against `body` before touching it. Cloud: PointCloud or WideCloud.
template <typename Cloud>
Cloud decodePcdAscii(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                     const std::filesystem::path& path);
template <typename Cloud>
Cloud decodePcdBinary(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                      const std::filesystem::path& path);
template <typename Cloud>
Cloud decodePcdCompressed(std::string_view body, const PcdHeader& header, const PcdLayout& layout,
                          const std::filesystem::path& path);

}  // namespace hba::io::detail
