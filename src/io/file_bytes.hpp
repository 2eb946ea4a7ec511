#pragma once
// Whole-file reading for the scan readers: one read into one buffer, so the
// decoders work on memory and never issue a read per point.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string_view>

namespace hba::io::detail {

class FileBytes {
 public:
  FileBytes() = default;
  FileBytes(std::unique_ptr<char[]> data, std::size_t size) : data_(std::move(data)), size_(size) {}
  const char* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  std::string_view view() const { return {data_.get(), size_}; }

 private:
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0;
};

// Reads the whole file. Throws hba::Error naming the file when it is missing,
// not a regular file (a folder, a FIFO, a link loop: hba/core/input_file.hpp)
// or unreadable.
FileBytes readFileBytes(const std::filesystem::path& path);

// Reads at most `max_bytes` from the start of the file (for header-only parsing).
FileBytes readFileHead(const std::filesystem::path& path, std::size_t max_bytes);

}  // namespace hba::io::detail
