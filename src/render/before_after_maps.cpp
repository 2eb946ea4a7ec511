#include "before_after_maps.hpp"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>

#include "core/progress.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/voxel/downsample.hpp"
#include "picture_points.hpp"
#include "scan_stream.hpp"

namespace hba::render {
namespace {

// Points of `scan` moved by `pose`, relative to `corner` (float precision
// near it), keeping those `keep` accepts.
PointCloud movedNear(const PointCloud& scan, const Pose& pose, const Vec3& corner,
                     const std::function<bool(const Vec3&)>& keep = {}) {
  PointCloud out;
  out.reserve(scan.size(), false);
  const Mat3 R = pose.R();
  const Vec3 t = pose * scan.origin;
  for (const Vec3f& p : scan.points) {
    const Vec3 world = R * p.cast<double>() + t;
    if (!keep || keep(world)) out.add((world - corner).cast<float>());
  }
  return out;
}

// A corner of the `grid` lattice near `p`, so that cells relative to it
// are the world's cells.
Vec3 latticeCorner(const Vec3& p, double grid) { return (p / grid).array().floor().matrix() * grid; }

eval::VoxelMerger mergerFor(const std::vector<Pose>& poses, double voxel) {
  eval::MapSettings settings;
  settings.voxel = voxel;
  // Relative to the first pose when it is far out (UTM), as merged maps are.
  const bool far = !poses.empty() && poses.front().t.cwiseAbs().maxCoeff() > 1e4;
  return eval::VoxelMerger(settings, far ? poses.front().t : Vec3::Zero());
}

void checkSizes(const io::ScanSource& scans, const std::array<const std::vector<Pose>*, 2>& poses) {
  for (const std::vector<Pose>* set : poses) {
    if (set->size() != scans.size()) {
      throw Error("there are " + std::to_string(scans.size()) + " scans but " + std::to_string(set->size()) +
                  " poses were given");
    }
  }
}

}  // namespace

double sensorReach(const io::ScanSource& scans, double voxel, double scans_voxel) {
  std::vector<double> ranges;
  for (const std::size_t i : {std::size_t{0}, scans.size() / 2, scans.size() - 1}) {
    if (i >= scans.size()) continue;
    const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
    for (std::size_t k = 0; k < scan.size(); ++k) ranges.push_back(scan.world(k).head<2>().norm());
  }
  if (ranges.empty()) return 0.0;
  const auto rank = static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(ranges.size() - 1));
  std::nth_element(ranges.begin(), ranges.begin() + rank, ranges.end());
  const double reach = ranges[static_cast<std::size_t>(rank)];
  return std::isfinite(reach) ? reach : 0.0;
}

double overviewVoxel(const std::array<const std::vector<Pose>*, 2>& poses, double reach, double voxel,
                     int pixels) {
  Eigen::AlignedBox2d box;
  for (const std::vector<Pose>* set : poses) {
    for (const Pose& pose : *set) box.extend(pose.t.head<2>());
  }
  const double span = box.isEmpty() ? 0.0 : box.sizes().maxCoeff() + 2.0 * reach;
  // Two voxels a pixel: at one or coarser, their centres land 1 or 2 to a
  // pixel in stripes, which the density shading shows as a grid.
  return std::max(voxel, span / (2.0 * std::max(pixels, 1)));
}

BeforeAfterMaps streamBeforeAfter(const io::ScanSource& scans,
                                  const std::array<const std::vector<Pose>*, 2>& poses, double voxel,
                                  int pixels, double moments_cell, double scans_voxel,
                                  const MemoryBudget& budget) {
  checkSizes(scans, poses);
  BeforeAfterMaps maps;
  maps.overview_voxel = overviewVoxel(poses, sensorReach(scans, voxel, scans_voxel), voxel, pixels);
  // The overview's points relative to the first pose (far from the world
  // origin, floats would lose the voxel).
  const Vec3 origin = latticeCorner(poses[1]->empty() ? Vec3::Zero() : poses[1]->front().t, 1.0);
  std::array<PicturePoints, 2> overview{PicturePoints(maps.overview_voxel, origin),
                                        PicturePoints(maps.overview_voxel, origin)};
  // Consecutive scans overlap: each chunk of them is merged on its own (in
  // parallel), so that the maps, merged in order, take a few points a scan.
  using Part = std::array<PointCloud, 2>;
  std::atomic<std::size_t> chunk_voxels{0};
  const std::function<Part(std::size_t)> read = [&](std::size_t chunk) {
    const std::size_t first = chunk * kChunk;
    const std::size_t end = std::min(scans.size(), first + kChunk);
    // Room for a chunk's voxels as the last chunk had them: no regrowing.
    const std::size_t expected = chunk_voxels.load(std::memory_order_relaxed);
    std::array<PicturePoints, 2> local{PicturePoints(maps.overview_voxel, origin, expected),
                                       PicturePoints(maps.overview_voxel, origin, expected)};
    for (std::size_t i = first; i < end; ++i) {
      const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
      // Coarser only where that halves the points at least.
      const PointCloud coarse =
          maps.overview_voxel >= 1.5 * voxel ? voxel::downsample(scan, maps.overview_voxel) : scan;
      for (std::size_t k = 0; k < 2; ++k) local[k].add(coarse, (*poses[k])[i]);
    }
    chunk_voxels.store(std::max(local[0].size(), local[1].size()), std::memory_order_relaxed);
    return Part{local[0].take(), local[1].take()};
  };
  const std::function<void(std::size_t, Part&)> merge = [&](std::size_t chunk, Part& part) {
    // Each map in scan order.
    tbb::parallel_invoke([&] { overview[0].add(part[0], Pose::identity()); },
                         [&] { overview[1].add(part[1], Pose::identity()); });
    if (budget.exceeded()) {
      throw budget.exceededBy("the picture's maps (" +
                              std::to_string(overview[0].size() + overview[1].size()) + " points after " +
                              std::to_string(std::min(scans.size(), (chunk + 1) * kChunk)) + " of " +
                              std::to_string(scans.size()) + " scans)");
    }
  };
  Progress progress("reading the scans for the picture", (scans.size() + kChunk - 1) / kChunk,
                    "chunks of " + std::to_string(kChunk) + " scans");
  streamScans(upTo((scans.size() + kChunk - 1) / kChunk), read, merge, progress);
  // Thickness from the merged voxels (each surface once, its range noise
  // averaged), in cells holding a few of them across.
  const double cell = std::max(moments_cell, 4.0 * maps.overview_voxel);
  auto finish = [&](std::size_t k) {
    maps.overview[k] = overview[k].take();
    maps.moments[k] = CellMoments(cell);
    for (std::size_t i = 0; i < maps.overview[k].size(); ++i) maps.moments[k].add(maps.overview[k].world(i));
  };
  tbb::parallel_invoke([&] { finish(0); }, [&] { finish(1); });
  return maps;
}

std::array<PointCloud, 2> squareMaps(const io::ScanSource& scans,
                                     const std::array<const std::vector<Pose>*, 2>& poses, double voxel,
                                     const Box2& square, double reach, double scans_voxel,
                                     const MemoryBudget& budget) {
  checkSizes(scans, poses);
  auto near = [&](const Pose& pose) {
    const double dx = std::max({square.xmin - pose.t.x(), 0.0, pose.t.x() - square.xmax});
    const double dy = std::max({square.ymin - pose.t.y(), 0.0, pose.t.y() - square.ymax});
    return std::hypot(dx, dy) <= reach;
  };
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (near((*poses[0])[i]) || near((*poses[1])[i])) indices.push_back(i);
  }
  auto inside = [&](const Vec3& p) {
    return p.x() >= square.xmin && p.x() <= square.xmax && p.y() >= square.ymin && p.y() <= square.ymax;
  };
  std::array<eval::VoxelMerger, 2> mergers{mergerFor(*poses[0], voxel), mergerFor(*poses[1], voxel)};
  const Vec3 corner = latticeCorner(Vec3(square.xmin, square.ymin, 0.0), voxel);
  using Part = std::array<PointCloud, 2>;
  const std::function<Part(std::size_t)> read = [&](std::size_t i) {
    const PointCloud scan = loadAt(scans, i, voxel, scans_voxel);
    Part part;
    for (std::size_t k = 0; k < 2; ++k) {
      if (near((*poses[k])[i])) part[k] = movedNear(scan, (*poses[k])[i], corner, inside);
    }
    return part;
  };
  const std::function<void(std::size_t, Part&)> merge = [&](std::size_t i, Part& part) {
    for (std::size_t k = 0; k < 2; ++k) {
      mergers[k].add(part[k], Pose(Quat::Identity(), corner), static_cast<std::uint32_t>(i));
    }
    if (budget.exceeded()) {
      throw budget.exceededBy("the picture's zoomed maps (" +
                              std::to_string(mergers[0].voxelCount() + mergers[1].voxelCount()) + " points)");
    }
  };
  Progress progress("reading the scans near the zoomed square", indices.size(), "scans");
  streamScans(indices, read, merge, progress);
  return {mergers[0].result(), mergers[1].result()};
}

}  // namespace hba::render
