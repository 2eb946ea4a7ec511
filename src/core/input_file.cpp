#include "core/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>
#include <system_error>

#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

// What stands at a path in place of a regular file, in words.
std::string kindOf(fs::file_type type) {
  switch (type) {
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    default:
      return "of an unknown kind";
  }
}

// Why status() found nothing usable at `path`: a loop and a dangling link are
// not "missing", and a stat that failed otherwise says why.
std::string absence(const fs::path& path, const std::error_code& ec, const std::string& missing) {
  if (ec == std::errc::too_many_symbolic_link_levels) return "is a symbolic link loop";
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) {
    return "cannot be examined: " + ec.message();
  }
  std::error_code link_ec;
  if (fs::is_symlink(fs::symlink_status(path, link_ec))) {
    return "is a broken symbolic link (to " + fs::read_symlink(path, link_ec).string() + ")";
  }
  return missing;
}

}  // namespace

void requireRegularFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  switch (status.type()) {
    case fs::file_type::regular:
      return;
    case fs::file_type::directory:
      failAt(path, "is a folder, not a file");
    case fs::file_type::not_found:
    case fs::file_type::none:
      failAt(path, absence(path, ec, "no such file"));
    default:
      failAt(path, "is not a regular file (" + kindOf(status.type()) + ")");
  }
}

bool regularFileIsPresent(const fs::path& path) {
  std::error_code ec;
  if (fs::symlink_status(path, ec).type() == fs::file_type::not_found) return false;
  requireRegularFile(path);
  return true;
}

void requireFolder(const fs::path& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) return;
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::none) {
    failAt(path, absence(path, ec, what + " not found"));
  }
  // A FIFO, socket or device: said what it is, as for every file read.
  if (status.type() != fs::file_type::regular) requireRegularFile(path);
  failAt(path, "is not a folder (expected a " + what + ")");
}

InputFile::InputFile(const fs::path& path) : path_(path) {
  requireRegularFile(path);
  // O_NONBLOCK: were the file swapped for a FIFO since the check, open()
  // returns at once instead of waiting for a writer. It changes nothing for
  // reads of a regular file.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) failAt(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat info = {};
  const bool regular = ::fstat(fd_, &info) == 0 && S_ISREG(info.st_mode);
  if (!regular) {
    ::close(fd_);
    fd_ = -1;
    requireRegularFile(path);  // says what it is now
    failAt(path, "is not a regular file");
  }
  size_ = static_cast<std::uint64_t>(info.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t InputFile::read(char* into, std::size_t bytes) {
  constexpr std::size_t kMaxChunk = std::size_t{1} << 30;  // Linux reads at most ~2 GiB at once
  std::size_t got = 0;
  while (got < bytes) {
    const ssize_t done = ::read(fd_, into + got, std::min(bytes - got, kMaxChunk));
    if (done < 0 && errno == EINTR) continue;
    if (done < 0) failAt(path_, std::string("read failed: ") + std::strerror(errno));
    if (done == 0) break;
    got += static_cast<std::size_t>(done);
  }
  return got;
}

std::string readTextFile(const fs::path& path) {
  InputFile file(path);
  std::string text;
  std::size_t used = 0;
  try {
    // The size is a hint: a file that grows while it is read is read whole.
    text.resize(static_cast<std::size_t>(file.size()));
    used = file.read(text.data(), text.size());
    while (used == text.size()) {
      text.resize(text.size() + 65536);
      used += file.read(text.data() + used, text.size() - used);
    }
  } catch (const std::bad_alloc&) {
    failAt(path, "too large to read into memory (" + std::to_string(file.size()) + " bytes)");
  }
  text.resize(used);
  const std::size_t mark = text.size() - withoutByteOrderMark(text).size();
  text.erase(0, mark);
  return text;
}

std::string_view withoutByteOrderMark(std::string_view text) {
  constexpr std::string_view kMark = "\xEF\xBB\xBF";
  if (text.substr(0, kMark.size()) == kMark) text.remove_prefix(kMark.size());
  return text;
}

}  // namespace hba
