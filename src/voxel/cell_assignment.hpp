#pragma once
// Which grid cell each point of a cloud falls in, numbered in the order the
// cells are first hit. Shared by downsampling and plane extraction, which
// both group every point of a large cloud by cell.
#include <cstdint>
#include <optional>
#include <vector>

#include "hba/core/types.hpp"

namespace hba::voxel {

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
