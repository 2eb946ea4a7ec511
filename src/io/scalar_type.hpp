#pragma once
// The numeric element types PCD and PLY files declare, and unaligned loads of
// one stored value converted to float.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hba::io::detail {

// The readers reinterpret file bytes directly; hba targets little-endian hosts.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "hba's scan readers assume a little-endian host");

enum class ScalarType : std::uint8_t {
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

constexpr std::size_t scalarSize(ScalarType type) {
  switch (type) {
    case ScalarType::Int8:
    case ScalarType::UInt8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Int64:
    case ScalarType::UInt64:
    case ScalarType::Float64:
      return 8;
  }
  return 0;
}

template <typename T>
inline T loadUnaligned(const char* p, bool big_endian) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (big_endian) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
      const unsigned char tmp = bytes[i];
      bytes[i] = bytes[sizeof(T) - 1 - i];
      bytes[sizeof(T) - 1 - i] = tmp;
    }
  }
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// Loads a float64 or float32 value stored at `p` as a double (other types via float).
inline double loadAsDouble(const char* p, ScalarType type, bool big_endian = false);

// Loads the value of `type` stored at `p` (any alignment) as a float.
inline float loadAsFloat(const char* p, ScalarType type, bool big_endian = false) {
  switch (type) {
    case ScalarType::Int8:
      return static_cast<float>(loadUnaligned<std::int8_t>(p, false));
    case ScalarType::UInt8:
      return static_cast<float>(loadUnaligned<std::uint8_t>(p, false));
    case ScalarType::Int16:
      return static_cast<float>(loadUnaligned<std::int16_t>(p, big_endian));
    case ScalarType::UInt16:
      return static_cast<float>(loadUnaligned<std::uint16_t>(p, big_endian));
    case ScalarType::Int32:
      return static_cast<float>(loadUnaligned<std::int32_t>(p, big_endian));
    case ScalarType::UInt32:
      return static_cast<float>(loadUnaligned<std::uint32_t>(p, big_endian));
    case ScalarType::Int64:
      return static_cast<float>(loadUnaligned<std::int64_t>(p, big_endian));
    case ScalarType::UInt64:
      return static_cast<float>(loadUnaligned<std::uint64_t>(p, big_endian));
    case ScalarType::Float32:
      return loadUnaligned<float>(p, big_endian);
    case ScalarType::Float64:
      return static_cast<float>(loadUnaligned<double>(p, big_endian));
  }
  return 0.0f;
}

inline double loadAsDouble(const char* p, ScalarType type, bool big_endian) {
  if (type == ScalarType::Float64) return loadUnaligned<double>(p, big_endian);
  return static_cast<double>(loadAsFloat(p, type, big_endian));
}

}  // namespace hba::io::detail
