#pragma once
// CRC-32 as zlib, PNG and MCAP compute it (IEEE 802.3, reflected,
// polynomial 0xEDB88320), fed piece by piece:
//   std::uint32_t crc = 0; crc = crc32Update(crc, a, n); crc = crc32Update(crc, b, m);
#include <cstddef>
#include <cstdint>

namespace hba::rec {

std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t size);

}  // namespace hba::rec
