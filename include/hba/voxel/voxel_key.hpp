#pragma once
// Integer coordinates of a cubic grid cell, and their hash.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tuple>

#include "hba/core/types.hpp"

namespace hba::voxel {

struct VoxelKey {
  std::int64_t x = 0;
  std::int64_t y = 0;
  std::int64_t z = 0;

  // The cell of edge `size` that contains `p` (cells are half-open: [k*size, (k+1)*size)).
  static VoxelKey of(const Vec3& p, double size) {
    return {cell(p.x() / size), cell(p.y() / size), cell(p.z() / size)};
  }

  // floor(v) as an integer, clamped so that absurd coordinates (1e30 m, NaN)
  // land in an edge cell instead of overflowing the conversion (undefined).
  static std::int64_t cell(double v) {
    constexpr double kLimit = 4.0e18;  // well inside int64
    if (!(v > -kLimit)) return static_cast<std::int64_t>(-kLimit);
    if (!(v < kLimit)) return static_cast<std::int64_t>(kLimit);
    // floor without a libm call (not inlined without SSE4.1): truncate, then
    // step down for negative non-integers. Same result as std::floor.
    const auto truncated = static_cast<std::int64_t>(v);
    return static_cast<double>(truncated) > v ? truncated - 1 : truncated;
  }

  bool operator==(const VoxelKey& o) const { return x == o.x && y == o.y && z == o.z; }
  // Lexicographic, used to visit cells in an order independent of hashing.
  bool operator<(const VoxelKey& o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};

struct VoxelKeyHash {
  std::size_t operator()(const VoxelKey& k) const {
    // Large odd multipliers spread neighbouring cells over the table.
    const auto h = static_cast<std::uint64_t>(k.x) * 73856093ULL ^
                   static_cast<std::uint64_t>(k.y) * 19349669ULL ^
                   static_cast<std::uint64_t>(k.z) * 83492791ULL;
    return static_cast<std::size_t>(h);
  }
};

}  // namespace hba::voxel
