#include "shared_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hba/core/error.hpp"
#include "procedural_path.hpp"

namespace hba::sim {
namespace {

PlanarPath slice(const PlanarPath& path, std::size_t first, std::size_t last, bool reverse) {
  PlanarPath out;
  for (std::size_t n = 0; n <= last - first; ++n) {
    const std::size_t i = reverse ? last - n : first + n;
    out.positions.push_back(path.positions[i]);
    out.headings.push_back(reverse ? std::remainder(path.headings[i] + M_PI, 2.0 * M_PI) : path.headings[i]);
  }
  return out;
}

}  // namespace

SharedPath::SharedPath(const TrajectoryConfig& config) : file_(config.file) {
  if (config.frames == 0) throw Error("simulate: the number of frames must be positive");
  if (!(config.frame_rate_hz > 0.0)) throw Error("simulate: the frame rate must be positive");
  if (!(config.sensor_height > 0.0)) throw Error("simulate: the sensor height must be positive");
  if (!config.file.empty()) {
    file_path_ = planarPathFromFile(config.file, std::numeric_limits<std::size_t>::max());
    file_arc_.push_back(0.0);
    for (std::size_t i = 1; i < file_path_.positions.size(); ++i) {
      file_arc_.push_back(file_arc_.back() + (file_path_.positions[i] - file_path_.positions[i - 1]).norm());
    }
    return;
  }
  if (!(config.speed > 0.0) || config.speed > 100.0) {
    throw Error("simulate: the speed must be in (0, 100] m/s");
  }
  step_ = config.speed / config.frame_rate_hz;
  loop_ = pathCurve(config);
}

PathStretch SharedPath::stretch(double start, std::size_t frames, bool reverse) const {
  PathStretch out;
  if (loop_) {
    out.path = walkCurve(*loop_, start, step_, frames, reverse);
    const double length = step_ * static_cast<double>(frames - 1);
    out.low = reverse ? start - length : start;
    out.high = reverse ? start : start + length;
    return out;
  }
  // The first pose at or beyond `start` metres along the file.
  const auto at = std::lower_bound(file_arc_.begin(), file_arc_.end(), start - 1e-9);
  if (at == file_arc_.end()) {
    failAt(file_, "a session starts " + std::to_string(start) + " m along this trajectory, which is only " +
                      std::to_string(file_arc_.back()) + " m long (lower --session-shift)");
  }
  const auto begin = static_cast<std::size_t>(at - file_arc_.begin());
  const std::size_t available = reverse ? begin + 1 : file_arc_.size() - begin;
  const std::size_t count = std::min(frames, available);
  const std::size_t first = reverse ? begin + 1 - count : begin;
  const std::size_t last = first + count - 1;
  out.path = slice(file_path_, first, last, reverse);
  out.low = file_arc_[first];
  out.high = file_arc_[last];
  return out;
}

PlanarPath SharedPath::span(double low, double high) const {
  if (loop_) {
    const auto frames = static_cast<std::size_t>(std::ceil((high - low) / step_ - 1e-9)) + 1;
    return walkCurve(*loop_, low, step_, frames, false);
  }
  const auto first = static_cast<std::size_t>(
      std::lower_bound(file_arc_.begin(), file_arc_.end(), low - 1e-9) - file_arc_.begin());
  const auto end = static_cast<std::size_t>(
      std::upper_bound(file_arc_.begin(), file_arc_.end(), high + 1e-9) - file_arc_.begin());
  return slice(file_path_, first, std::max(first, end - 1), false);
}

}  // namespace hba::sim
