#pragma once
// Byte layout of LAS files (ASPRS LAS 1.4 R15, with the 1.0-1.3 headers it
// extends): public header field offsets, header sizes per version, and the
// smallest record length of each point data record format.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hba::io::detail {

// Public header field offsets (identical in every version up to the end of
// the 1.2 header; 1.3 and 1.4 only append fields).
namespace las_field {
constexpr std::size_t kSignature = 0;
constexpr std::size_t kGlobalEncoding = 6;
constexpr std::size_t kVersionMajor = 24;
constexpr std::size_t kVersionMinor = 25;
constexpr std::size_t kSystemIdentifier = 26;
constexpr std::size_t kGeneratingSoftware = 58;
constexpr std::size_t kCreationDay = 90;
constexpr std::size_t kCreationYear = 92;
constexpr std::size_t kHeaderSize = 94;
constexpr std::size_t kPointDataOffset = 96;
constexpr std::size_t kVlrCount = 100;
constexpr std::size_t kPointFormat = 104;
constexpr std::size_t kRecordLength = 105;
constexpr std::size_t kLegacyPointCount = 107;
constexpr std::size_t kLegacyPointsByReturn = 111;  // uint32[5]
constexpr std::size_t kScale = 131;                 // double[3]
constexpr std::size_t kOffset = 155;                // double[3]
constexpr std::size_t kBounds = 179;                // max x, min x, max y, min y, max z, min z
constexpr std::size_t kWaveformStart = 227;         // 1.3 on
constexpr std::size_t kFirstEvlrStart = 235;        // 1.4 on
constexpr std::size_t kEvlrCount = 243;
constexpr std::size_t kPointCount = 247;      // uint64
constexpr std::size_t kPointsByReturn = 255;  // uint64[15]
}  // namespace las_field

constexpr std::size_t kLasTextFieldBytes = 32;  // system identifier, generating software
constexpr std::size_t kLasHeaderSize12 = 227;   // versions 1.0 to 1.2
constexpr std::size_t kLasHeaderSize13 = 235;
constexpr std::size_t kLasHeaderSize14 = 375;
constexpr std::size_t kLasVlrHeaderSize = 54;   // each VLR's own header
constexpr std::size_t kLasVlrLengthField = 20;  // its uint16 "record length after header"

// The format byte's two high bits flag LAZ compression (LASzip's convention).
constexpr std::uint8_t kLasCompressedBits = 0xC0;
constexpr int kLasMaxPointFormat = 10;

// Smallest record of each point data record format: x y z intensity and the
// fixed fields; a file may declare longer records (extra bytes).
constexpr std::uint16_t kLasMinRecordLength[kLasMaxPointFormat + 1] = {20, 28, 26, 34, 57, 63,
                                                                       30, 36, 38, 59, 67};

// Fields at the same place in every point format.
namespace las_point {
constexpr std::size_t kX = 0;  // int32 x y z, scaled
constexpr std::size_t kIntensity = 12;
}  // namespace las_point

// The rest of a point format 6 record, the one hba writes.
namespace las_point6 {
constexpr std::size_t kReturns = 14;  // return number (bits 0-3), number of returns (4-7)
constexpr std::size_t kPointSourceId = 20;
constexpr std::size_t kGpsTime = 22;
constexpr std::uint16_t kLength = 30;
}  // namespace las_point6

// Unaligned little-endian loads and stores (hba targets little-endian hosts,
// see scalar_type.hpp).
template <typename T>
T loadLittleEndian(const char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

template <typename T>
void storeLittleEndian(char* at, T value) {
  std::memcpy(at, &value, sizeof(T));
}

}  // namespace hba::io::detail
