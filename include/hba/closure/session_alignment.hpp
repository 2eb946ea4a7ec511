#pragma once
// Placing one session in another's frame when nothing relates their frames
// (docs/closure.md): places sampled along both are described by a signature
// that does not depend on heading; for each place of the session, the most
// alike places of the reference are tried as loop candidates with a full
// turn of heading and a few metres of shift (verifyLoop); the placements the
// verified pairs imply must agree. Assumes z roughly up in both sessions
// (gravity-aligned odometry), as the bird's-eye search does.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/closure/loop_check.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::closure {

struct SessionAlignmentSettings {
  double sample_spacing_m = 10.0;  // a place every this much path of each session
  std::size_t max_samples = 60;    // per session, spread evenly beyond
  std::size_t shortlist = 3;       // reference places tried for each place of the session
  double reach_m = 8.0;            // shift searched around a tried coincidence
  // Verified pairs agree when their placements differ by less than this.
  double agree_m = 0.3;
  double agree_deg = 1.0;
  std::size_t min_agreeing = 2;     // and so many must agree
  std::size_t enough_agreeing = 4;  // stop trying once so many agree
  LoopCheckSettings check;          // its search bounds are set per pair
};

struct SessionAlignment {
  bool found = false;
  Pose world_from_session;  // maps the session's frame into the reference's
  std::size_t tried = 0;    // pairs verified
  std::size_t verified = 0;
  std::size_t agreeing = 0;
  std::string reason;  // why not found
};

// `reference_poses` and `session_poses` each in their own frame; the scans
// as the pyramid loads them (downsampled). Deterministic.
SessionAlignment alignSession(const io::ScanSource& reference_scans, const std::vector<Pose>& reference_poses,
                              const io::ScanSource& session_scans, const std::vector<Pose>& session_poses,
                              const SessionAlignmentSettings& settings);

// The places of a path sampled every `spacing` m of it (the first frame
// first), at most `max_count` spread evenly over them.
std::vector<std::size_t> samplePlaces(const std::vector<Pose>& poses, double spacing, std::size_t max_count);

}  // namespace hba::closure
