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
    return {static_cast<std::int64_t>(std::floor(p.x() / size)),
            static_cast<std::int64_t>(std::floor(p.y() / size)),
            static_cast<std::int64_t>(std::floor(p.z() / size))};
  }

  bool operator==(const VoxelKey& o) const { return x == o.x && y == o.y && z == o.z; }
  // Lexicographic, used to visit cells in an order independent of hashing.
  bool operator<(const VoxelKey& o) const {
    return std::tie(x, y, z) < std::tie(o.x, o.y, o.z);
  }
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
