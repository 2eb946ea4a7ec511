#include "hba/voxel/downsample.hpp"

#include <unordered_map>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

struct CellSum {
  Vec3 position = Vec3::Zero();
  double intensity = 0.0;
  std::size_t count = 0;
};

}  // namespace

// Rule: each occupied voxel becomes the centroid of its points (and the mean
// intensity). The centroid averages range noise instead of keeping one noisy
// sample, which matters for plane residuals. Output order is the order in
// which voxels are first hit while scanning the input, so the result does not
// depend on the hash table's iteration order.
PointCloud downsample(const PointCloud& cloud, double voxel_size) {
  if (!(voxel_size > 0.0)) return cloud;
  const bool with_intensity = cloud.hasIntensity();

  std::unordered_map<VoxelKey, std::size_t, VoxelKeyHash> cell_of_key;
  cell_of_key.reserve(cloud.size());
  std::vector<CellSum> cells;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.points[i].cast<double>();
    const auto [it, inserted] = cell_of_key.try_emplace(VoxelKey::of(p, voxel_size), cells.size());
    if (inserted) cells.emplace_back();
    CellSum& cell = cells[it->second];
    cell.position += p;
    if (with_intensity) cell.intensity += cloud.intensity[i];
    ++cell.count;
  }

  PointCloud out;
  out.reserve(cells.size(), with_intensity);
  for (const CellSum& cell : cells) {
    const double inv = 1.0 / static_cast<double>(cell.count);
    const Vec3f centroid = (cell.position * inv).cast<float>();
    if (with_intensity) {
      out.add(centroid, static_cast<float>(cell.intensity * inv));
    } else {
      out.add(centroid);
    }
  }
  return out;
}

}  // namespace hba::voxel
