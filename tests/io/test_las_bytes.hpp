#pragma once
// LAS files built byte by byte from the specification's tables, apart from
// hba's own writer: the reader tests feed it every version and point format,
// and the writer tests read hba's output field by field with it.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace hba::test {

template <typename T>
void putBytes(std::string& bytes, std::size_t at, T value) {
  std::memcpy(&bytes[at], &value, sizeof(T));
}

template <typename T>
T getBytes(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, &bytes[at], sizeof(T));
  return value;
}

struct LasPointInts {
  std::int32_t x, y, z;
  std::uint16_t intensity;
};

struct LasSpec {
  int minor = 2;
  int format = 1;
  int record_length = 28;
  double scale = 0.01;
  double offset[3] = {0.0, 0.0, 0.0};
  std::vector<int> vlr_payloads;  // byte counts of VLRs between header and points
  bool legacy_count = true;       // fill the 32-bit count
  bool wide_count = true;         // fill the 64-bit count (1.4)
};

inline std::size_t lasHeaderSize(int minor) { return minor <= 2 ? 227 : minor == 3 ? 235 : 375; }

inline std::string lasBytes(const LasSpec& spec, const std::vector<LasPointInts>& points) {
  const std::size_t header_size = lasHeaderSize(spec.minor);
  std::string bytes(header_size, '\0');
  bytes.replace(0, 4, "LASF");
  bytes[24] = 1;
  bytes[25] = static_cast<char>(spec.minor);
  bytes.replace(58, 9, "test-made");
  putBytes<std::uint16_t>(bytes, 94, static_cast<std::uint16_t>(header_size));
  putBytes<std::uint32_t>(bytes, 100, static_cast<std::uint32_t>(spec.vlr_payloads.size()));
  bytes[104] = static_cast<char>(spec.format);
  putBytes<std::uint16_t>(bytes, 105, static_cast<std::uint16_t>(spec.record_length));
  if (spec.legacy_count) putBytes<std::uint32_t>(bytes, 107, static_cast<std::uint32_t>(points.size()));
  for (int a = 0; a < 3; ++a) {
    putBytes<double>(bytes, 131 + 8 * a, spec.scale);
    putBytes<double>(bytes, 155 + 8 * a, spec.offset[a]);
  }
  if (spec.minor >= 4 && spec.wide_count) putBytes<std::uint64_t>(bytes, 247, points.size());
  for (const int payload : spec.vlr_payloads) {
    std::string vlr(54 + static_cast<std::size_t>(payload), 'v');
    putBytes<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(payload));
    bytes += vlr;
  }
  putBytes<std::uint32_t>(bytes, 96, static_cast<std::uint32_t>(bytes.size()));
  for (const LasPointInts& p : points) {
    std::string record(static_cast<std::size_t>(spec.record_length), '\x5a');  // filler the reader must skip
    putBytes(record, 0, p.x);
    putBytes(record, 4, p.y);
    putBytes(record, 8, p.z);
    putBytes(record, 12, p.intensity);
    bytes += record;
  }
  return bytes;
}

}  // namespace hba::test
