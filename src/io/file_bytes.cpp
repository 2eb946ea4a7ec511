#include "file_bytes.hpp"

#include <cstdint>
#include <new>
#include <string>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// Reads up to `limit` bytes; the size on disk is only a hint, so a file that
// shrinks or grows while we read is still handled without overrunning.
FileBytes readUpTo(const fs::path& path, std::size_t limit) {
  InputFile file(path);  // a regular file: a FIFO named like a scan would hang
  const std::uint64_t size_on_disk = file.size();
  const std::size_t capacity = size_on_disk < limit ? static_cast<std::size_t>(size_on_disk) : limit;
  std::unique_ptr<char[]> data;
  try {
    data.reset(new char[capacity == 0 ? 1 : capacity]);
  } catch (const std::bad_alloc&) {
    failAt(path, "too large to read into memory (" + std::to_string(capacity) + " bytes)");
  }
  const std::size_t got = file.read(data.get(), capacity);
  return FileBytes(std::move(data), got);
}

}  // namespace

FileBytes readFileBytes(const fs::path& path) { return readUpTo(path, SIZE_MAX); }

FileBytes readFileHead(const fs::path& path, std::size_t max_bytes) { return readUpTo(path, max_bytes); }

}  // namespace hba::io::detail
