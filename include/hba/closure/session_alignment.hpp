#pragma once
// Placing one session in another's frame when nothing relates their frames
// (docs/closure.md). Places are sampled along both sessions; each is a local
// submap merged around it in its own sensor frame. Every submap is described
// by FPFH descriptors; a session place votes for the reference places whose
// descriptors its own resemble most; each shortlisted pair is registered
// globally (descriptor matches, RANSAC, point-to-plane ICP: no assumption on
// the relative pose, z up or not) and then verified by the plane BA of
// verifyLoop; the placements the verified pairs imply must agree.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/closure/feature_registration.hpp"
#include "hba/closure/loop_check.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::closure {

struct SessionAlignmentSettings {
  double sample_spacing_m = 5.0;       // a place every this much path of each session
  std::size_t max_samples = 20;        // per session, spread evenly beyond
  double submap_path_m = 6.0;          // a place's submap: the frames this much path either side
  std::size_t max_submap_frames = 40;  // either side, at most
  // Descriptor voxel (m); 0: a twentieth of the submaps' median range, within 0.1..1 m.
  double feature_voxel_m = 0.0;
  std::size_t shortlist = 3;           // reference places registered with each place of the session
  std::size_t votes_per_place = 400;   // a session place's descriptors that vote
  std::size_t voted_per_place = 1500;  // a reference place's descriptors that can be voted for
  RegistrationSettings registration;
  // A registered pair goes on to the plane BA with this share of the
  // session's submap on the reference's surfaces.
  double min_fitness = 0.3;
  std::size_t max_trials = 60;  // registered pairs, most voted first
  // Verified pairs agree when their placements differ by less than this:
  // more than the noise of one, less than a repetitive place's period.
  double agree_m = 1.0;
  double agree_deg = 2.0;
  std::size_t min_agreeing = 2;     // and so many must agree
  std::size_t enough_agreeing = 4;  // stop trying once so many agree
  LoopCheckSettings check;          // the verification (its coarse search is not used)
};

// One registered pair of places, for the report.
struct SessionPairTrial {
  std::size_t reference_frame = 0;
  std::size_t session_frame = 0;
  std::size_t votes = 0;
  std::size_t matches = 0;  // mutual descriptor matches
  std::size_t inliers = 0;  // of them, agreeing with the robust estimate
  double fitness = 0.0;
  bool verified = false;
  std::string outcome;  // "verified", or why rejected
};

struct SessionAlignment {
  bool found = false;
  Pose world_from_session;  // maps the session's frame into the reference's
  std::size_t tried = 0;    // pairs registered
  std::size_t verified = 0;
  std::size_t agreeing = 0;
  double feature_voxel_m = 0.0;
  std::size_t reference_places = 0, session_places = 0;
  std::vector<SessionPairTrial> trials;
  // Wall time (s): describing the places, voting, registering and verifying pairs.
  double seconds_describing = 0.0, seconds_voting = 0.0, seconds_registering = 0.0;
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
