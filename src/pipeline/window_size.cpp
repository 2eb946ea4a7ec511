#include "hba/pipeline/window_size.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hba/core/error.hpp"

namespace hba::pipeline {

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

HbaSettings withWindowSize(HbaSettings settings, const WindowSize& size) {
  settings.window = size.window;
  settings.stride = size.stride;
  return settings;
}

}  // namespace hba::pipeline
