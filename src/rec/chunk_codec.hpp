#pragma once
// A recording chunk's records, decompressed: "none", "lz4" (the LZ4 frame
// format), "zstd" or "bz2". Another compression, or data that does not decompress to the
// size the chunk declares, throws hba::Error naming `where`.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hba::rec {

std::vector<std::uint8_t> decompressChunk(const std::string& compression, const std::uint8_t* data,
                                          std::size_t size, std::size_t uncompressed_size,
                                          const std::string& where);

}  // namespace hba::rec
