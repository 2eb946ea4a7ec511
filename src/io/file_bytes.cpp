#include "file_bytes.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <system_error>

#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FileHandle = std::unique_ptr<std::FILE, FileCloser>;

// Opens a regular file for reading, with a message that says what is wrong
// when it cannot be (fopen alone "succeeds" on a directory).
FileHandle openRegularFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) failAt(path, "no such file");
  if (fs::is_directory(status)) failAt(path, "is a directory, not a file");
  errno = 0;
  FileHandle file(std::fopen(path.c_str(), "rb"));
  if (!file) failAt(path, std::string("cannot open: ") + std::strerror(errno));
  return file;
}

// Reads up to `limit` bytes; the size on disk is only a hint, so a file that
// shrinks or grows while we read is still handled without overrunning.
FileBytes readUpTo(const fs::path& path, std::size_t limit) {
  FileHandle file = openRegularFile(path);
  std::error_code ec;
  const std::uintmax_t size_on_disk = fs::file_size(path, ec);
  if (ec) failAt(path, "cannot get the file size: " + ec.message());
  const std::size_t capacity = size_on_disk < limit ? static_cast<std::size_t>(size_on_disk) : limit;
  std::unique_ptr<char[]> data;
  try {
    data.reset(new char[capacity == 0 ? 1 : capacity]);
  } catch (const std::bad_alloc&) {
    failAt(path, "too large to read into memory (" + std::to_string(capacity) + " bytes)");
  }
  errno = 0;
  const std::size_t got = std::fread(data.get(), 1, capacity, file.get());
  if (got < capacity && std::ferror(file.get())) {
    failAt(path, std::string("read failed: ") + std::strerror(errno));
  }
  return FileBytes(std::move(data), got);
}

}  // namespace

FileBytes readFileBytes(const fs::path& path) { return readUpTo(path, SIZE_MAX); }

FileBytes readFileHead(const fs::path& path, std::size_t max_bytes) { return readUpTo(path, max_bytes); }

}  // namespace hba::io::detail
