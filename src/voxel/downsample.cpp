#include "hba/voxel/downsample.hpp"

#include "cell_assignment.hpp"

namespace hba::voxel {
namespace {

// Running sums of one occupied voxel, in double so that thousands of float
// points average without loss.
struct CellSum {
  Vec3 position = Vec3::Zero();
  double intensity = 0.0;
  std::uint32_t count = 0;
};

}  // namespace

// Rule: each occupied voxel becomes the centroid of its points (and the mean
// intensity). The centroid averages range noise instead of keeping one noisy
// sample, which matters for plane residuals. Output order is the order in
// which voxels are first hit while scanning the input, and each centroid sums
// its points in input order, so the result depends on neither hashing nor
// the key representation.
//
// Cells come from one pass through a flat hash table (cell_assignment.cpp):
// no sorting and no allocation per cell, which matters because every scan
// and every keyframe goes through here.
PointCloud downsample(const PointCloud& cloud, double voxel_size, std::size_t points_per_cell) {
  if (!(voxel_size > 0.0)) return cloud;
  // A scan at scan voxels has about a cell a point: a table sized for that
  // never regrows. Clouds of millions start smaller, so that a coarse voxel
  // does not cost a huge table. A table far larger than its cells is mostly
  // page faults and cache misses (a keyframe of ten scans' plane points:
  // 8 MB for 1 MB of cells).
  if (points_per_cell == 0) points_per_cell = cloud.size() <= (std::size_t{1} << 20) ? 1 : 4;
  const CellAssignment cells = assignCells(cloud.points, voxel_size, points_per_cell);
  const bool with_intensity = cloud.hasIntensity();
  std::vector<CellSum> sums(cells.cells());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    CellSum& sum = sums[cells.cell_of_point[i]];
    sum.position += cloud.points[i].cast<double>();
    if (with_intensity) sum.intensity += cloud.intensity[i];
    ++sum.count;
  }

  PointCloud out;
  out.origin = cloud.origin;  // the points stay relative to it
  out.reserve(sums.size(), with_intensity);
  for (const CellSum& sum : sums) {
    const double inv = 1.0 / static_cast<double>(sum.count);
    const Vec3f centroid = (sum.position * inv).cast<float>();
    if (with_intensity) {
      out.add(centroid, static_cast<float>(sum.intensity * inv));
    } else {
      out.add(centroid);
    }
  }
  return out;
}

}  // namespace hba::voxel
