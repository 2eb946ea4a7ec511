#pragma once
// How many frames a layer-1 window holds when `window` is 0 (automatic).
//
// A window's BA must place its frames better than the odometry already did.
// Ten dense scans (a simulated VLP-16 at 0.1 m: 196 000 points) do; ten
// sparse ones (nclt's HDL-32E keyframes, 2 900 points each after
// downsampling; a Livox scan, 4 000) do not: their relative poses came out
// further from the truth than the odometry's, and chained up the pyramid
// they bent a 1.1 km loop by 30 m (docs/history/benchmarks.md). So an
// automatic window holds at least kWindowPoints points (as the windows see
// them, after downsample_scans), never fewer than the paper's ten frames.
// The default since 2026-11-30: with the final voxel following the window
// (final_voxel.hpp) the hierarchy alone is kept on every sequence measured,
// hku1 and nclt at 83 % and 93 % of one global BA's MME gain
// (docs/pyramid.md, "Automatic windows").
#include "hba/io/scan_source.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

inline constexpr double kWindowPoints = 150000.0;
// The paper's window (Table I): the least an automatic window holds.
inline constexpr int kPaperWindow = 10;
inline constexpr int kMinAutomaticWindow = kPaperWindow;
inline constexpr int kMaxAutomaticWindow = 60;

struct WindowSize {
  int window = 0;
  int stride = 0;
  bool automatic = false;        // the window was chosen here (window 0)
  double points_per_scan = 0.0;  // what it was chosen from (0 when given)
};

// The window and stride a run with `settings` uses, for scans of
// `points_per_scan` points (after downsample_scans) on average. A window
// given keeps its value; a stride of 0 is half the window. An automatic
// window is kept above a stride given. Throws hba::ValueError when the
// stride given is not below the window given.
WindowSize chooseWindowSize(const HbaSettings& settings, double points_per_scan);

// `settings` with the window and stride of `size`.
HbaSettings withWindowSize(HbaSettings settings, const WindowSize& size);

}  // namespace hba::pipeline
