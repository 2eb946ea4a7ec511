#pragma once
// LZF (liblzf) compression of one block, as PCD binary_compressed stores it.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace hba::io::detail {

// LZF emits at most 264 output bytes per 3 input bytes (a longest back
// reference), so a block claiming to inflate further is lying about its sizes.
constexpr std::size_t kMaxLzfExpansion = 88;

// Decompresses `compressed`, which must inflate to exactly `expected_size`
// bytes. Throws hba::Error naming `path` for corrupt data or lying sizes.
std::unique_ptr<char[]> lzfDecompress(std::string_view compressed, std::size_t expected_size,
                                      const std::filesystem::path& path);

// Appends the LZF compression of `raw` to `out` and returns its size in bytes.
std::size_t lzfCompressAppend(std::string_view raw, std::string& out, const std::filesystem::path& path);

}  // namespace hba::io::detail
