#include "hba/pyramid/window_size.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hba/core/error.hpp"
#include "hba/pyramid/memory_estimate.hpp"

namespace hba::pyramid {

WindowSize chooseWindowSize(const HbaSettings& settings, double points_per_scan) {
  WindowSize size;
  size.window = settings.window;
  if (size.window == 0) {
    size.automatic = true;
    size.points_per_scan = points_per_scan;
    const double frames =
        points_per_scan > 0.0 ? std::ceil(kWindowPoints / points_per_scan) : kMaxAutomaticWindow;
    size.window = static_cast<int>(std::clamp<double>(frames, kMinAutomaticWindow, kMaxAutomaticWindow));
    // A stride given stays below the window chosen.
    if (settings.stride > 0) size.window = std::max(size.window, settings.stride + 1);
  }
  size.stride = settings.stride > 0 ? settings.stride : std::max(1, size.window / 2);
  if (size.stride >= size.window) {
    throw ValueError("setting stride must be below window (--stride " + std::to_string(size.stride) +
                     " >= --window " + std::to_string(size.window) + ")");
  }
  return size;
}

WindowSize chooseWindowSize(const HbaSettings& settings, const io::ScanSource& scans) {
  if (settings.window > 0) return chooseWindowSize(settings, 0.0);
  // The scans read, as they are: hku1 in an lz4 bag weighted by its message
  // sizes came to 3 900 points a scan against 4 036 from its folder, and so
  // to other windows (39 scans against 38) and other poses.
  return chooseWindowSize(settings, sampleScanDensity(scans, settings).sampled_points);
}

HbaSettings withWindowSize(HbaSettings settings, const WindowSize& size) {
  settings.window = size.window;
  settings.stride = size.stride;
  return settings;
}

}  // namespace hba::pyramid
