#pragma once
// Parsing and checking a LAS public header, shared by readLasHeader and readLas.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "hba/io/las.hpp"

namespace hba::io::detail {

// Parses the header at `data` (`available` bytes read from the start of a
// file of `file_size` bytes) and checks every field the points depend on
// against itself and the file size. Throws hba::Error naming `path`.
LasHeader parseLasHeader(const char* data, std::size_t available, std::uint64_t file_size,
                         const std::filesystem::path& path);

}  // namespace hba::io::detail
