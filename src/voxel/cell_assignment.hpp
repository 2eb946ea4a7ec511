#pragma once
// Which grid cell each point of a cloud falls in, numbered in the order the
// cells are first hit. Shared by downsampling and plane extraction, which
// both group every point of a large cloud by cell.
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "hba/core/types.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {

// VoxelKey::of for one edge length. Dividing by a power of two is
// multiplying by its exact inverse: the same keys without three divisions a
// point (plane voxels are 4 m halved; scan voxels like 0.1 m keep the
// division).
class KeyOf {
 public:
  explicit KeyOf(double size) : size_(size), inverse_(1.0 / size) {
    int exponent = 0;
    power_of_two_ = std::frexp(size, &exponent) == 0.5;
  }
  VoxelKey operator()(const Vec3f& point) const {
    const Vec3 p = point.cast<double>();
    return VoxelKey{cell(p.x()), cell(p.y()), cell(p.z())};
  }
  // The key's x alone.
  std::int64_t x(const Vec3f& point) const { return cell(static_cast<double>(point.x())); }

 private:
  std::int64_t cell(double v) const { return VoxelKey::cell(power_of_two_ ? v * inverse_ : v / size_); }
  double size_;
  double inverse_;
  bool power_of_two_ = false;
};

struct CellAssignment {
  std::vector<std::uint32_t> cell_of_point;        // one per point
  std::vector<std::uint32_t> first_point_of_cell;  // one per cell, ascending
  std::size_t cells() const { return first_point_of_cell.size(); }
};

// Cells of edge `size` (half-open [k*size, (k+1)*size), as VoxelKey::of).
// Non-finite points land in the edge cells VoxelKey gives them.
// `points_per_cell`: the expected share, which sizes the hash table before
// its first doubling (a guess only: the table grows as needed, and the
// result does not depend on it).
CellAssignment assignCells(const std::vector<Vec3f>& points, double size, std::size_t points_per_cell = 4);

// The cells of edge `coarse_size` (an edge of `fine`'s cells times a power
// of two) that hold `fine`'s cells of the same `points`: exactly what
// assignCells(points, coarse_size) gives, from one pass of key checks
// instead of a pass of hashing. Empty where some point's coarse cell is not
// its fine cell's (rounding at an edge that is no such multiple).
std::optional<CellAssignment> coarsenCells(const CellAssignment& fine, const std::vector<Vec3f>& points,
                                           double coarse_size);

// Point ids grouped by cell (counting sort: ids ascend within each cell).
struct CellMembers {
  std::vector<std::uint32_t> begin;  // cells + 1 offsets into ids
  std::vector<std::uint32_t> ids;
};
CellMembers membersOf(const CellAssignment& assignment);

}  // namespace hba::voxel
