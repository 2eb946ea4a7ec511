#include "lzf_block.hpp"

#include <lzf.h>

#include <climits>
#include <string>

#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

std::unique_ptr<char[]> lzfDecompress(std::string_view compressed, std::size_t expected_size,
                                      const fs::path& path) {
  if (compressed.size() > UINT_MAX || expected_size > UINT_MAX) {
    failAt(path, "compressed block is larger than LZF allows");
  }
  if (expected_size / kMaxLzfExpansion > compressed.size()) {
    failAt(path, "compressed block of " + std::to_string(compressed.size()) + " bytes cannot hold " +
                     std::to_string(expected_size) + " bytes of points (the sizes in the file lie)");
  }
  std::unique_ptr<char[]> raw(new char[expected_size == 0 ? 1 : expected_size]);
  // liblzf checks every back reference and length against both buffers
  // (CHECK_INPUT), so garbage input fails here instead of overrunning.
  const unsigned int produced =
      lzf_decompress(compressed.data(), static_cast<unsigned int>(compressed.size()), raw.get(),
                     static_cast<unsigned int>(expected_size));
  if (produced != expected_size) {
    failAt(path, "corrupt compressed data: LZF decoding gave " + std::to_string(produced) +
                     " bytes instead of " + std::to_string(expected_size));
  }
  return raw;
}

std::size_t lzfCompressAppend(std::string_view raw, std::string& out, const fs::path& path) {
  if (raw.empty()) return 0;
  if (raw.size() > UINT_MAX / 2) failAt(path, "cloud too large for binary_compressed");
  // Incompressible input grows by about 1/32; leave room so compression
  // always succeeds.
  const std::size_t capacity = raw.size() + raw.size() / 16 + 64;
  const std::size_t start = out.size();
  out.resize(start + capacity);
  const unsigned int written = lzf_compress(raw.data(), static_cast<unsigned int>(raw.size()), &out[start],
                                            static_cast<unsigned int>(capacity));
  if (written == 0) failAt(path, "LZF compression failed");
  out.resize(start + written);
  return written;
}

}  // namespace hba::io::detail
