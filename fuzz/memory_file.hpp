#pragma once
// The hba readers take a path, not bytes. A fuzz input is handed to them as an
// anonymous in-memory file (memfd) reached through /proc/self/fd, so no input
// touches the disk and nothing is left behind when the fuzzer is killed.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace hba::fuzz {

class MemoryFile {
 public:
  MemoryFile() : fd_(::memfd_create("hba_fuzz_input", 0)) {
    if (fd_ < 0) std::abort();  // the harness itself cannot work: stop loudly
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~MemoryFile() { ::close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  // Replaces the content with `data` and returns the path that reads it.
  const std::filesystem::path& hold(const std::uint8_t* data, std::size_t size) {
    if (::ftruncate(fd_, 0) != 0) std::abort();
    std::size_t written = 0;
    while (written < size) {
      const ssize_t n = ::pwrite(fd_, data + written, size - written, static_cast<off_t>(written));
      if (n <= 0) std::abort();
      written += static_cast<std::size_t>(n);
    }
    return path_;
  }

 private:
  int fd_;
  std::filesystem::path path_;
};

// One file reused by every input of a fuzzing process.
inline MemoryFile& sharedMemoryFile() {
  static MemoryFile file;
  return file;
}

}  // namespace hba::fuzz
