#pragma once
// Little-endian fields read from a byte range, every read bounds-checked: a
// record or message shorter than its fields say throws hba::Error naming
// `what` (the file and the record or message). In CDR (ROS 2's
// serialization) each number is aligned to its size from the payload's
// start, and strings carry their terminating zero.
#include <cstdint>
#include <cstring>
#include <string>

#include "hba/core/error.hpp"

namespace hba::rec {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size, std::string what)
      : data_(data), size_(size), what_(std::move(what)) {}

  // From here on, CDR: aligned from this position.
  void startCdr() {
    cdr_ = true;
    origin_ = pos_;
  }
  bool cdr() const { return cdr_; }

  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }
  const std::uint8_t* here() const { return data_ + pos_; }

  template <typename T>
  T read() {
    if (cdr_) skip((sizeof(T) - (pos_ - origin_) % sizeof(T)) % sizeof(T));
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_ + pos_, sizeof(T));  // the hosts we build for are little-endian
    pos_ += sizeof(T);
    return value;
  }
  std::uint8_t u8() { return read<std::uint8_t>(); }
  std::uint32_t u32() { return read<std::uint32_t>(); }
  std::uint64_t u64() { return read<std::uint64_t>(); }
  double f64() { return read<double>(); }
  // A ROS time or duration: seconds and nanoseconds, as seconds.
  double time() {
    const std::uint32_t sec = u32();
    const std::uint32_t nsec = u32();
    return static_cast<double>(sec) + 1e-9 * static_cast<double>(nsec);
  }
  // A length-prefixed string (uint32 length, then the bytes).
  std::string string() {
    const std::uint32_t length = u32();
    need(length);
    std::string text(reinterpret_cast<const char*>(data_ + pos_), length);
    pos_ += length;
    if (cdr_) {
      if (text.empty() || text.back() != '\0') fail("a CDR string without its terminating zero");
      text.pop_back();
    }
    return text;
  }
  // A length-prefixed byte array: where it starts, and its length.
  std::pair<const std::uint8_t*, std::size_t> bytes() {
    const std::uint32_t length = u32();
    need(length);
    const std::uint8_t* start = data_ + pos_;
    pos_ += length;
    return {start, length};
  }
  void skip(std::size_t n) {
    need(n);
    pos_ += n;
  }
  // An array's element count, checked against what is left (each element
  // takes at least `min_bytes`), so a corrupt count cannot ask for gigabytes.
  std::uint32_t count(std::size_t min_bytes) {
    const std::uint32_t n = u32();
    if (min_bytes > 0 && n > remaining() / min_bytes)
      fail("an array claims " + std::to_string(n) + " elements");
    return n;
  }

  [[noreturn]] void fail(const std::string& problem) const { throw Error(what_ + ": " + problem); }

 private:
  void need(std::size_t n) const {
    if (n > size_ - pos_) {
      fail("ends early (" + std::to_string(n) + " bytes needed at byte " + std::to_string(pos_) + " of " +
           std::to_string(size_) + ")");
    }
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::string what_;
  bool cdr_ = false;
  std::size_t origin_ = 0;
};

}  // namespace hba::rec
