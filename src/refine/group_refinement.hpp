#pragma once
// The coarse half of the refinement, for sequences longer than one
// refinement block (docs/pyramid.md, "Long sequences"): after the blocks,
// consecutive frames are tied into rigid groups, each group's scans merged
// into one cloud, and one plane BA over all groups (solved exactly: few
// unknowns) places them. It sees what blocks of consecutive frames cannot:
// planes shared by passes far apart in time (a second lap over the first)
// and the sequence's long, weak bends.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "refinement.hpp"

namespace hba::refine {

// Frames per group for a sequence of `frames`: enough that there are at
// most `max_groups` groups, and never fewer than `min_frames`.
std::size_t groupSize(std::size_t frames, std::size_t max_groups, std::size_t min_frames);

// Frames [first, end) of one group.
struct GroupSpan {
  std::size_t first = 0;
  std::size_t end = 0;
};

// The frames of `current` with each group's rigid move (`moves[k]`, applied
// on the left) spread along the sequence: a group's move holds exactly at
// its centre frame, and a frame between two centres takes the two moves'
// placements of it blended by its position between them (positions
// linearly, orientations along the shortest arc); frames before the first
// centre or after the last take that group's move. Applied group by group
// instead, the moves would step at every group's edge by the whole
// difference between neighbouring groups.
std::vector<Pose> spreadGroupMoves(const std::vector<GroupSpan>& groups, const std::vector<Pose>& moves,
                                   const std::vector<Pose>& current);

// Moves the groups of `current` to fit one plane BA over all of them, each
// as a rigid body, and spreads their moves to the frames
// (spreadGroupMoves). `input` gives the motion prior's reference (the
// odometry's steps between groups). Returns
// `current` unchanged, with a warning, if the groups' map would get
// blurrier (report.rejected), or if there are fewer than three groups.
// Position priors stay out: a group of ten frames may hold one, and the
// planes between groups of an open scene are too weak to stop each group
// following its prior's noise (0.5 m steps between groups on a simulated
// 5 km drive with priors of sigma 0.5 m); the final re-anchoring places the
// groups' result instead.
std::vector<Pose> refineGroups(const io::ScanSource& scans, const std::vector<Pose>& input,
                               const std::vector<Pose>& current, const RefineSettings& settings,
                               GroupRefinementReport& report, StageNotes& notes);

}  // namespace hba::refine
