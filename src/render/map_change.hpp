#pragma once
// Where a map changed (private to render): the thickness of its planes and
// the square where optimization made them thinnest, for the zoomed
// before/after row of before_after.png.
#include <optional>
#include <unordered_map>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::render {

// The thickness (m) of a map's planes, per `cell` voxel of the world grid:
// the square root of the smallest eigenvalue of the covariance of the
// voxel's points, where they form a plane (a wall seen twice, 4 cm apart, is
// about 2 cm thick; a crisp one a few mm); -1 elsewhere (too few points, or
// no plane: foliage, edges).
class PlaneThickness {
 public:
  PlaneThickness(const PointCloud& map, double cell);
  double cell() const { return cell_; }
  // The thickness of each point's voxel, in the map's order.
  std::vector<float> perPoint(const PointCloud& map) const;
  const std::unordered_map<voxel::VoxelKey, float, voxel::VoxelKeyHash>& voxels() const { return voxels_; }

 private:
  double cell_;
  std::unordered_map<voxel::VoxelKey, float, voxel::VoxelKeyHash> voxels_;
};

// The square (side `side`, m) where the planes got thinner the most, summed
// over its voxels; nothing if no square's planes got thinner by 2 mm on
// average (a rigid shift of the whole map changes nothing). Both on one cell.
std::optional<Box2> mostThinnedRegion(const PlaneThickness& before, const PlaneThickness& after, double side);

}  // namespace hba::render
