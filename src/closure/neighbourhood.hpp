#pragma once
// The local map of one end of a loop candidate: the scans around it merged
// into that end frame's coordinates with the current (locally accurate)
// relative poses.
#include <cstddef>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::closure {

struct FrameRange {
  std::size_t first = 0;  // inclusive
  std::size_t last = 0;   // inclusive
  bool overlaps(const FrameRange& other) const { return first <= other.last && other.first <= last; }
};

// Frames within `half_width` of `centre`, clipped to [0, count).
FrameRange neighbourhoodFrames(std::size_t centre, std::size_t half_width, std::size_t count);

// The scans of `frames` in the frame of `centre`, downsampled to `voxel` (m).
// Deterministic: scans load in parallel and merge in frame order.
PointCloud mergeNeighbourhood(const io::ScanSource& scans, const std::vector<Pose>& poses, std::size_t centre,
                              const FrameRange& frames, double voxel);

}  // namespace hba::closure
