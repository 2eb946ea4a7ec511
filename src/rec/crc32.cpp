#include "crc32.hpp"

#include <zlib.h>

namespace hba::rec {

// zlib's CRC-32 is MCAP's (IEEE 802.3, reflected), and about twice as fast as
// a table-driven one of our own on the chunks of point clouds.
std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(::crc32_z(crc, data, size));
}

}  // namespace hba::rec
