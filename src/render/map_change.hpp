#pragma once
// Where a map changed (private to render): the thickness of its planes and
// the square where optimization made them thinnest, for the zoomed
// before/after row of before_after.png.
#include <optional>
#include <unordered_map>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/render/map_picture.hpp"
#include "hba/voxel/key_table.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::render {

// Point moments per `cell` voxel of the world grid, each relative to its
// cell's corner (precise far from the world origin); sums of many scans'
// points, so that plane thickness needs no merged map in memory.
class CellMoments {
 public:
  struct Moments {
    double count = 0.0;
    Vec3 sum = Vec3::Zero();
    Mat3 outer = Mat3::Zero();
  };
  explicit CellMoments(double cell) : cell_(cell) {}
  double cell() const { return cell_; }
  // Returns the number of the cell `world` fell in (its index below).
  std::uint32_t add(const Vec3& world);
  void merge(const CellMoments& other);
  // Room for `cells` cells without regrowing (a guess is fine).
  void reserve(std::size_t cells);
  // Cells in the order first touched.
  std::size_t size() const { return keys_.size(); }
  const voxel::VoxelKey& key(std::size_t i) const { return keys_[i]; }
  const Moments& moments(std::size_t i) const { return moments_[i]; }

 private:
  Moments& at(const voxel::VoxelKey& key, std::uint32_t* number = nullptr);
  double cell_;
  voxel::VoxelIndex index_;
  std::vector<voxel::VoxelKey> keys_;
  std::vector<Moments> moments_;
};

// The thickness (m) of one cell's points where they form a plane (see
// PlaneThickness), -1 otherwise.
float planeThicknessOf(const CellMoments::Moments& m);

// The thickness (m) of a map's planes, per `cell` voxel of the world grid:
// the square root of the smallest eigenvalue of the covariance of the
// voxel's points, where they form a plane (a wall seen twice, 4 cm apart, is
// about 2 cm thick; a crisp one a few mm); -1 elsewhere (too few points, or
// no plane: foliage, edges).
class PlaneThickness {
 public:
  PlaneThickness(const PointCloud& map, double cell);
  explicit PlaneThickness(const CellMoments& moments);
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
