#pragma once
// The path several sessions share: a procedural loop walked by arc length, or
// a trajectory file's poses (one a frame). A session drives a stretch of it
// from any point, in either direction; the world is built around the span
// every session covers.
#include <cstddef>
#include <optional>
#include <vector>

#include "closed_curve.hpp"
#include "hba/sim/trajectory.hpp"

namespace hba::sim {

struct PathStretch {
  PlanarPath path;
  double low = 0.0, high = 0.0;  // the arc lengths (m) it covers, low <= high
};

class SharedPath {
 public:
  // Throws hba::Error as makeTrajectory does for invalid settings.
  explicit SharedPath(const TrajectoryConfig& config);

  // `frames` frames from `start` metres along the path, backwards if
  // `reverse`. A loop wraps; a file's stretch stops at its first or last pose.
  PathStretch stretch(double start, std::size_t frames, bool reverse) const;
  // The path driven forwards from arc length `low` to `high`.
  PlanarPath span(double low, double high) const;

 private:
  double step_ = 0.0;                // m per frame (loops)
  std::optional<ClosedCurve> loop_;  // set for procedural paths
  PlanarPath file_path_;             // the whole file otherwise
  std::vector<double> file_arc_;     // arc length at each of its poses
  std::filesystem::path file_;
};

}  // namespace hba::sim
