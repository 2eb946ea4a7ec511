#pragma once
// The points a report page shows (private to render): the merged map
// thinned to a budget, one point per occupied world voxel (the first in
// scan order), each kept in its own scan's frame with that scan's index so
// that the page places it with any pose set (input, optimized).
#include <cstdint>
#include <vector>

#include "hba/core/memory_budget.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::render {

// 20 bytes a point: a 2 M point page holds 40 MB.
struct PagePoint {
  std::uint32_t scan = 0;
  float intensity = 0.0f;       // 0 when the scans have none
  Vec3f local = Vec3f::Zero();  // in the scan's sensor frame
};

struct PagePoints {
  std::vector<PagePoint> points;  // scans ascending
  bool has_intensity = false;     // some point has a non-zero intensity
  double voxel = 0.0;             // the world voxel (m) the map was thinned at
  double kept_share = 1.0;        // of the points one a voxel, the share kept to fit the budget
  std::size_t size() const { return points.size(); }
};

// Calls `visit(i, world)` for each of `points` placed by `poses` (world in
// double, less `origin`), converting one pose to a matrix a scan.
template <typename Visit>
void forEachPlaced(const std::vector<PagePoint>& points, const std::vector<Pose>& poses, const Vec3& origin,
                   Visit&& visit) {
  std::uint32_t scan = ~0u;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].scan != scan) {
      scan = points[i].scan;
      R = poses[scan].R();
      t = poses[scan].t - origin;
    }
    visit(i, Vec3(R * points[i].local.cast<double>() + t));
  }
}

// At most `budget` points of the map of `scans` placed by `poses`: one per
// world voxel (the first in scan order), the voxel starting at `start_voxel`
// and growing while the map outgrows the budget by a quarter, then an even
// share of them kept. Scans that come downsampled at `scans_voxel` (m, 0:
// as recorded) are not downsampled again at that voxel or finer. Throws MemoryExceeded once the process
// outgrows `memory`, hba::Error on a size mismatch.
PagePoints samplePagePoints(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t budget,
                            double start_voxel, double scans_voxel = 0.0, const MemoryBudget& memory = {});

}  // namespace hba::render
