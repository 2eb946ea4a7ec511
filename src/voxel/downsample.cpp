#include "hba/voxel/downsample.hpp"

#include <algorithm>
#include <cstdint>
#include <tuple>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

struct KeyedPoint {
  VoxelKey key;
  std::uint32_t index = 0;
};

struct Cell {
  std::uint32_t first_index = 0;  // smallest input index in the cell
  std::uint32_t begin = 0;        // range in the sorted points
  std::uint32_t end = 0;
};

}  // namespace

// Rule: each occupied voxel becomes the centroid of its points (and the mean
// intensity). The centroid averages range noise instead of keeping one noisy
// sample, which matters for plane residuals. Output order is the order in
// which voxels are first hit while scanning the input, so the result does not
// depend on hashing or sorting details.
//
// Points are grouped by sorting (key, index) pairs rather than through a hash
// map: no allocation per cell, and several times faster on scan-sized clouds.
PointCloud downsample(const PointCloud& cloud, double voxel_size) {
  if (!(voxel_size > 0.0)) return cloud;
  const bool with_intensity = cloud.hasIntensity();
  const std::size_t n = cloud.size();

  std::vector<KeyedPoint> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    keyed[i] = {VoxelKey::of(cloud.points[i].cast<double>(), voxel_size), static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end(), [](const KeyedPoint& a, const KeyedPoint& b) {
    return std::tie(a.key.x, a.key.y, a.key.z, a.index) < std::tie(b.key.x, b.key.y, b.key.z, b.index);
  });

  std::vector<Cell> cells;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && keyed[j].key == keyed[i].key) ++j;
    cells.push_back({keyed[i].index, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
    i = j;
  }
  std::sort(cells.begin(), cells.end(),
            [](const Cell& a, const Cell& b) { return a.first_index < b.first_index; });

  PointCloud out;
  out.reserve(cells.size(), with_intensity);
  for (const Cell& cell : cells) {
    Vec3 position = Vec3::Zero();
    double intensity = 0.0;
    // Sum in input order (indices ascend within a cell), as the hash-map version did.
    for (std::uint32_t k = cell.begin; k < cell.end; ++k) {
      position += cloud.points[keyed[k].index].cast<double>();
      if (with_intensity) intensity += cloud.intensity[keyed[k].index];
    }
    const double inv = 1.0 / static_cast<double>(cell.end - cell.begin);
    const Vec3f centroid = (position * inv).cast<float>();
    if (with_intensity) {
      out.add(centroid, static_cast<float>(intensity * inv));
    } else {
      out.add(centroid);
    }
  }
  return out;
}

}  // namespace hba::voxel
