#include "chunk_codec.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <memory>

#include "hba/core/error.hpp"

namespace hba::rec {
namespace {

std::vector<std::uint8_t> lz4Frame(const std::uint8_t* data, std::size_t size, std::size_t expected,
                                   const std::string& where) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw Error(where + ": cannot start an lz4 decompression");
  }
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  std::vector<std::uint8_t> out(expected);
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  while (in_pos < size) {
    std::size_t out_size = out.size() - out_pos;
    std::size_t in_size = size - in_pos;
    const std::size_t hint =
        LZ4F_decompress(context.get(), out.data() + out_pos, &out_size, data + in_pos, &in_size, nullptr);
    if (LZ4F_isError(hint)) {
      throw Error(where + ": the lz4 data is corrupt (" + LZ4F_getErrorName(hint) + ")");
    }
    in_pos += in_size;
    out_pos += out_size;
    if (hint == 0) break;  // the frame is complete
    if (in_size == 0 && out_size == 0) throw Error(where + ": the lz4 data ends early");
  }
  out.resize(out_pos);
  return out;
}

std::vector<std::uint8_t> bz2(const std::uint8_t* data, std::size_t size, std::size_t expected,
                              const std::string& where) {
  std::vector<std::uint8_t> out(expected);
  auto out_size = static_cast<unsigned int>(expected);
  const int status = BZ2_bzBuffToBuffDecompress(
      reinterpret_cast<char*>(out.data()), &out_size, const_cast<char*>(reinterpret_cast<const char*>(data)),
      static_cast<unsigned int>(size), /*small=*/0, /*verbosity=*/0);
  if (status != BZ_OK)
    throw Error(where + ": the bz2 data is corrupt (bzip2 error " + std::to_string(status) + ")");
  out.resize(out_size);
  return out;
}

std::vector<std::uint8_t> zstdFrame(const std::uint8_t* data, std::size_t size, std::size_t expected,
                                    const std::string& where) {
  std::vector<std::uint8_t> out(expected);
  const std::size_t got = ZSTD_decompress(out.data(), out.size(), data, size);
  if (ZSTD_isError(got)) throw Error(where + ": the zstd data is corrupt (" + ZSTD_getErrorName(got) + ")");
  out.resize(got);
  return out;
}

}  // namespace

std::vector<std::uint8_t> decompressChunk(const std::string& compression, const std::uint8_t* data,
                                          std::size_t size, std::size_t uncompressed_size,
                                          const std::string& where) {
  // A corrupt size must not ask for gigabytes: no codec here packs a
  // chunk of point clouds a thousand times smaller.
  if (compression != "none" && uncompressed_size > 1024 * size + (std::size_t{1} << 20)) {
    throw Error(where + ": the chunk claims " + std::to_string(uncompressed_size) + " bytes from " +
                std::to_string(size) + " compressed: it is corrupt");
  }
  std::vector<std::uint8_t> out;
  if (compression == "none") {
    out.assign(data, data + size);
  } else if (compression == "lz4") {
    out = lz4Frame(data, size, uncompressed_size, where);
  } else if (compression == "bz2") {
    out = bz2(data, size, uncompressed_size, where);
  } else if (compression == "zstd") {
    out = zstdFrame(data, size, uncompressed_size, where);
  } else {
    throw Error(where + ": unknown chunk compression '" + compression +
                "' (hba reads none, lz4, zstd and bz2)");
  }
  if (out.size() != uncompressed_size) {
    throw Error(where + ": the chunk holds " + std::to_string(out.size()) + " bytes, its header says " +
                std::to_string(uncompressed_size));
  }
  return out;
}

}  // namespace hba::rec
