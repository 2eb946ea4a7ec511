#pragma once
// The finest voxel the pyramid's plane BAs associate at, coarsened where
// the scans are sparse.
//
// A plane the BA can trust is one most of whose points one scan saw. Where
// a scan puts only a few points in a voxel (a VLP-16 thinned to 0.5 m: two
// in a metre cube), the plane test's minimum is reached only by pooling
// many scans, each seeing a different side of whatever is there: on curved
// surfaces (trees, bushes) those pools pass the plane test and pull the
// frames to make them flat. Ten-frame windows on such scans turned their
// frames 0.25 degrees from the truth where the odometry was within 0.05
// (docs/pyramid.md, "Where error enters"). So the coarse-to-fine
// association stops one halving earlier while one scan holds fewer than
// half the plane test's minimum points in a voxel (`min_points / 2`, on
// average over its points). Larger windows pool more scans into each
// voxel: the wanted points shrink in proportion (a window of w scans wants
// 10 / w of it). On nclt, 53-scan windows at 1 m took the hierarchy alone
// to MME -3.297 where 2 m voxels left it at -3.281; ten-scan windows at 1 m
// made its map blurrier (docs/pyramid.md, "Automatic windows").
#include <functional>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/pipeline/window_size.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

struct FinalVoxel {
  double setting = 0.0;  // local.final_voxel_size as given (m)
  double chosen = 0.0;   // where the windows' association ends (m)
  bool coarsened = false;
  // Points of one scan in the voxel of each of its points, on average, at
  // the setting and at the voxel chosen (0 when not measured).
  double scan_points_at_setting = 0.0;
  double scan_points_at_chosen = 0.0;
};

// The points one scan should hold in a voxel for windows of
// settings.window scans (min_points / 2 at the paper's ten, kPaperWindow,
// for which the rule was first set).
double scanPointsWanted(const HbaSettings& settings);

// The points of `scan` that share a cubic voxel of edge `size` with each
// of its points, averaged over the points: sum n^2 / sum n over its cells.
double scanPointsPerVoxel(const PointCloud& scan, double size);

// The voxel for scans whose points per voxel of a given size are
// `points_per_voxel(size)` (scanPointsPerVoxel's measure): local.final_voxel_size
// doubled while below scanPointsWanted and below the root voxel
// (settings.window must be resolved: not 0). Unchanged
// when settings.adapt_final_voxel is off or the coarse-to-fine is (0).
FinalVoxel chooseFinalVoxel(const HbaSettings& settings,
                            const std::function<double(double)>& points_per_voxel);

// The same, measured on scans downsampled to settings.scan_voxel as the
// windows see them (the plan's sample: readScanSample).
FinalVoxel chooseFinalVoxel(const HbaSettings& settings, const std::vector<PointCloud>& sample);

// `settings` whose windows' and top BA's association ends at `voxel.chosen`
// or their own final voxel, whichever is coarser (never above their root).
HbaSettings withFinalVoxel(HbaSettings settings, const FinalVoxel& voxel);

}  // namespace hba::pipeline
