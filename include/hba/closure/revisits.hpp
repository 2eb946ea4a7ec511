#pragma once
// Revisit detection by the current poses (docs/closure.md): frames that come
// back within reach of an earlier place, far apart along the path. Odometry
// drifts, so "within reach" grows with the path driven between the two
// visits; each candidate carries the search bounds its verification needs.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::closure {

struct RevisitSettings {
  // Bound of the odometry's drift: position error per metre of path driven
  // between the visits, and heading error in degrees per metre.
  double drift = 0.05;
  double drift_deg_per_m = 0.05;
  // Two frames at most this far apart (after allowing for drift) may see
  // the same place: about the range at which scans share structure.
  double reach_m = 10.0;
  // Less path than this between two frames is the same pass, not a revisit.
  double min_separation_m = 50.0;
  // At most one candidate per this much path of the later visit.
  double spacing_m = 10.0;
  // Caps of the search a candidate asks of its verification.
  double max_search_m = 30.0;
  double max_search_deg = 30.0;
};

struct RevisitCandidate {
  std::size_t from = 0;  // the earlier visit
  std::size_t to = 0;    // the later one
  double path_m = 0.0;   // driven between them
  double distance_m = 0.0;
  double search_radius_m = 0.0;  // the translation the verification must search
  double search_yaw_deg = 0.0;
  bool cross_session = false;  // the two frames belong to different sessions
};

// How far two visits `path_m` of driving apart may have drifted from each
// other: the shift and heading the verification must search (drift times
// path, capped at the largest search).
struct DriftSearch {
  double radius_m = 0.0;
  double yaw_deg = 0.0;
};
DriftSearch driftSearch(double path_m, const RevisitSettings& settings);

// The path driven up to each frame (m), from 0 at the first.
std::vector<double> cumulativePath(const std::vector<Pose>& poses);

// Ordered by `to`. Frames of different sessions (`session_starts`, see
// sessions.hpp) are revisits however little path lies between them, and
// their search is the largest allowed: the sessions' own frames are only
// as close as their initial alignment. Throws hba::Error for settings that
// are not positive.
std::vector<RevisitCandidate> findRevisits(const std::vector<Pose>& poses, const RevisitSettings& settings,
                                           const std::vector<std::size_t>& session_starts = {});

}  // namespace hba::closure
