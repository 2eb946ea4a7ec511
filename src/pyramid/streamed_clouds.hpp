#pragma once
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pyramid/window_plan.hpp"

namespace hba::pyramid {

// The clouds (scans or keyframes) of a range of frames, loaded in parallel
// when a batch of windows needs them and dropped once the batches have moved
// past them, so that memory holds a few windows' worth of clouds.
class StreamedClouds {
 public:
  explicit StreamedClouds(const io::ScanSource& source);

  // Holds the clouds of frames [first, end): drops those before `first`,
  // loads those not held yet. Later calls must not start before `first`.
  void keepRange(std::size_t first, std::size_t end);

  // A held cloud (throws std::out_of_range if it is not held).
  const PointCloud* get(std::size_t i) const { return &held_.at(i); }
  // The held clouds of a window's frames, in order.
  std::vector<const PointCloud*> cloudsOf(const Window& window) const;

  // Points of every frame loaded so far, each frame counted once.
  std::size_t pointsLoaded() const { return points_loaded_; }
  // Each frame loaded so far, with its points, in frame order.
  std::vector<std::pair<std::size_t, std::size_t>> framesLoaded() const;

 private:
  const io::ScanSource& source_;
  std::map<std::size_t, PointCloud> held_;
  std::vector<bool> counted_;              // per frame of the source: its points are in points_loaded_
  std::vector<std::size_t> frame_points_;  // per frame of the source, once counted
  std::size_t points_loaded_ = 0;
};

}  // namespace hba::pyramid
