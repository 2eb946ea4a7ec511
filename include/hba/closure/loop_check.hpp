#pragma once
// Verification of a loop-closure candidate: a pair of frames that
// a user or a revisit detector claims see the same place. The scans around
// each end are merged into two local maps, aligned coarsely in bird's-eye
// view when the guess may be far off, then by a plane BA of the two maps as
// one window; the pair is accepted only when shared planes hold the result
// in all six directions. See docs/closure.md.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"
#include "hba/graph/information.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::closure {

struct LoopPair {
  std::size_t from = 0;  // frame indices; from < to is not required
  std::size_t to = 0;
  // Guess of T_from^-1 * T_to; without one, the relative pose of the current poses.
  std::optional<Pose> relative;
};

// The frames merged around each end of a pair (first, last; inclusive).
// Where the sequence holds several sessions, an end's frames must stay in its own.
struct LoopEnds {
  std::pair<std::size_t, std::size_t> from;
  std::pair<std::size_t, std::size_t> to;
};

struct LoopCheckSettings {
  // Frames either side of each end merged into its local map: one scan of a
  // 16-beam sensor holds too few points on walls for a plane test.
  std::size_t neighbourhood_frames = 5;
  double neighbourhood_voxel = 0.1;  // m, downsampling of a merged local map

  // Coarse search (bird's-eye view, z up): +- this around the guess. Both 0
  // trust the guess and go straight to the plane BA.
  double search_radius_m = 0.0;
  double search_yaw_deg = 0.0;
  double search_cell_m = 0.5;  // bird's-eye cell of the coarse level (the fine level halves it)
  // A cell is structure (not ground) when its points span this height (m).
  double structure_height_m = 0.5;
  // Share of the `to` map's structure cells that must land on the `from`
  // map's at the best offset; fewer: the maps do not look alike.
  double min_search_score = 0.5;
  // Ambiguity: a second peak at least `ambiguous_distance_m` (or
  // `ambiguous_yaw_deg`) from the best with this share of its score.
  double max_second_peak_ratio = 0.9;
  double ambiguous_distance_m = 2.0;
  double ambiguous_yaw_deg = 5.0;

  // The joint plane BA, coarse to fine as the windows do; its other
  // settings are ba::BaSettings' own (stated here: they differ from the
  // windows'). The two ends start from a guess metres off: three
  // associations at the final voxel, where a window needs one.
  double voxel_size = 4.0;        // m, first association
  double final_voxel_size = 1.0;  // m, last association (the Hessian's)
  int association_rounds = 3;

  // Acceptance.
  std::size_t min_shared_planes = 30;
  double min_overlap = 0.6;  // share of the `to` map's plane points on shared planes
  double max_rms_m = 0.05;   // point-to-plane RMS on the shared planes
  // Every direction must be held: within translation (and within rotation),
  // the least certain direction's standard deviation may be at most this many
  // times the most certain one's (a corridor, a flat field fail).
  double max_sigma_ratio = 10.0;
  // And in absolute terms (from the information below).
  double max_sigma_m = 0.05;
  double max_sigma_deg = 0.25;

  // The information of the result, scaled as the window factors are.
  graph::InformationSettings information;
};

struct LoopCheck {
  bool accepted = false;
  std::string reason;  // why rejected (for the report), or ""
  Pose relative;       // T_from^-1 * T_to as the planes place it
  // In the tangent of hba/core/relative_pose_error.hpp, like graph::RelativePoseFactor.
  Mat6 information = Mat6::Zero();
  std::size_t shared_planes = 0;  // planes with points from both neighbourhoods
  double overlap = 0.0;           // share of the `to` map's plane points on shared planes
  double rms_m = 0.0;             // point-to-plane RMS on the shared planes after the BA
  double correction_m = 0.0;      // how far the result is from the guess
  double correction_deg = 0.0;
  double search_score = 0.0;  // coarse search: best score and the best far from it (0 without a search)
  double search_second_score = 0.0;
  double sigma_m = 0.0;  // least certain translation and rotation directions (1 sigma)
  double sigma_deg = 0.0;
};

// `scans` are the layer-1 clouds as the pyramid loads them (already
// downsampled; any io::ScanSource), `poses` the current layer-1 poses
// (locally accurate, globally drifting). Thread-safe and deterministic for any
// thread count. Throws hba::Error on frames out of range, poses that do not
// match the scans, from == to, or invalid settings; a pair the scans do not
// support is not an error but a rejection with a reason.
// `ends`: the frames merged around each end; without, `neighbourhood_frames`
// either side, clipped to the sequence.
LoopCheck verifyLoop(const io::ScanSource& scans, const std::vector<Pose>& poses, const LoopPair& pair,
                     const LoopCheckSettings& settings, const std::optional<LoopEnds>& ends = std::nullopt);

// Throws hba::Error naming the first invalid setting.
void validate(const LoopCheckSettings& settings);

}  // namespace hba::closure
