#pragma once
// The core of session and map alignment (hba/closure/session_alignment.hpp):
// places of a reference and of a session described, matched, registered and
// verified; the placements of the verified pairs must agree.
#include <cstddef>
#include <vector>

#include "hba/closure/session_alignment.hpp"
#include "neighbourhood.hpp"

namespace hba::closure {

// The frames within `path_m` of path either side of `centre`, at most
// `max_frames` each side, inside `bounds` (its session).
FrameRange submapFrames(const std::vector<Pose>& poses, std::size_t centre, double path_m,
                        std::size_t max_frames, FrameRange bounds);

// One side of an alignment: a session (places on its path, each the submap
// of the frames around it) or a map cut into tiles (each tile one frame, its
// own submap, posed at its centre).
struct Side {
  const io::ScanSource& scans;
  const std::vector<Pose>& poses;
  std::vector<std::size_t> places;  // frames
  bool tiles = false;

  FrameRange submap(std::size_t frame, const SessionAlignmentSettings& s) const {
    if (tiles) return {frame, frame};
    return submapFrames(poses, frame, s.submap_path_m, s.max_submap_frames, {0, poses.size() - 1});
  }
};

// A twentieth of the median range of the sides' place scans: the spacing at
// which a scene's surfaces still have shape (a room: 0.2 m, a street: 1 m).
double featureVoxel(const std::vector<const Side*>& sides);

// world_from_session maps the session's frame into the reference's.
SessionAlignment alignSides(const Side& reference, const Side& session, double voxel,
                            const SessionAlignmentSettings& settings);

}  // namespace hba::closure
