#pragma once
// The maps a before/after picture is drawn from, streamed from the scans
// with bounded memory (private to render). One pass reads every scan once
// and merges it with both pose sets at a voxel matched to the picture's
// resolution; plane thickness comes from those merged voxels. A second
// pass reads only the scans taken near the zoomed square and keeps their
// points inside it at full resolution.
#include <array>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/map_picture.hpp"
#include "map_change.hpp"

namespace hba::render {

struct BeforeAfterMaps {
  std::array<PointCloud, 2> overview;  // before, after: merged at overview_voxel
  // Of the overview's points, in cells of `moments_cell` or four overview
  // voxels, whichever is larger.
  std::array<CellMoments, 2> moments{CellMoments(1.0), CellMoments(1.0)};
  double overview_voxel = 0.0;
};

// How far a scan's points reach horizontally (95th percentile over the
// first, middle and last scans at `voxel`, so that scans that come
// downsampled at `scans_voxel` give the same; m).
double sensorReach(const io::ScanSource& scans, double voxel = 0.0, double scans_voxel = 0.0);

// The overview's voxel: `voxel`, or coarser where the map (the
// trajectories' extent plus `reach` either side) is so large that half of
// one of `pixels` across it is coarser: a picture shows no finer.
double overviewVoxel(const std::array<const std::vector<Pose>*, 2>& poses, double reach, double voxel,
                     int pixels);

// Every scan read once (in parallel batches, merged in scan order: the same
// maps for any thread count), downsampled to `voxel` in its own frame
// unless `scans_voxel` (the voxel the scans come downsampled at) is as large.
// Throws MemoryExceeded once the maps outgrow `budget`.
BeforeAfterMaps streamBeforeAfter(const io::ScanSource& scans,
                                  const std::array<const std::vector<Pose>*, 2>& poses, double voxel,
                                  int pixels, double moments_cell, double scans_voxel = 0.0,
                                  const MemoryBudget& budget = {});

// The points inside `square` of the scans whose pose lies within `reach`
// (m) of it, merged at `voxel`, for each pose set (`scans_voxel` and
// `budget` as above).
std::array<PointCloud, 2> squareMaps(const io::ScanSource& scans,
                                     const std::array<const std::vector<Pose>*, 2>& poses, double voxel,
                                     const Box2& square, double reach, double scans_voxel = 0.0,
                                     const MemoryBudget& budget = {});

}  // namespace hba::render
