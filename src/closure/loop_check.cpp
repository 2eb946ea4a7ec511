#include "hba/closure/loop_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "birds_eye_search.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "held_directions.hpp"
#include "neighbourhood.hpp"
#include "plane_overlap.hpp"

namespace hba::closure {
namespace {

template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char text[320];
  std::snprintf(text, sizeof(text), pattern, args...);
  return text;
}

void checkInput(const io::ScanSource& scans, const std::vector<Pose>& poses, const LoopPair& pair,
                const LoopCheckSettings& settings) {
  validate(settings);
  if (poses.size() != scans.size()) {
    throw Error("loop check: " + std::to_string(poses.size()) + " poses for " + std::to_string(scans.size()) +
                " scans");
  }
  if (pair.from >= scans.size() || pair.to >= scans.size()) {
    throw Error("loop check: pair (" + std::to_string(pair.from) + ", " + std::to_string(pair.to) +
                ") out of range (" + std::to_string(scans.size()) + " scans)");
  }
  if (pair.from == pair.to) throw Error("loop check: pair (" + std::to_string(pair.from) + ", same frame)");
}

ba::BaSettings jointWindowSettings(const LoopCheckSettings& settings) {
  ba::BaSettings ba;
  ba.planes.voxel_size = settings.voxel_size;
  ba.final_voxel_size = settings.final_voxel_size;
  ba.association_rounds = settings.association_rounds;
  // The two ends are far apart along the path: no odometry relates them.
  ba.motion_prior.enabled = false;
  // The check measures where the ends meet, even when they already do.
  ba.significant_gain = 0.0;
  return ba;
}

// Rounded to 0.01, without "-0.00".
std::string vectorText(const Vec3& v) {
  const Vec3 rounded = (v * 100.0).array().round() / 100.0 + 0.0;
  return format("(%.2f, %.2f, %.2f)", rounded.x() + 0.0, rounded.y() + 0.0, rounded.z() + 0.0);
}

// The first acceptance test the result fails, or "".
std::string rejection(const LoopCheck& check, const HeldDirections& held, const LoopCheckSettings& s) {
  if (check.shared_planes < s.min_shared_planes) {
    return format("%zu shared planes, fewer than %zu: the neighbourhoods do not see the same surfaces",
                  check.shared_planes, s.min_shared_planes);
  }
  if (check.overlap < s.min_overlap) {
    return format("overlap %.2f below %.2f: most planes of the `to` map have no counterpart", check.overlap,
                  s.min_overlap);
  }
  if (check.rms_m > s.max_rms_m) {
    return format("point-to-plane RMS %.3f m above %.3f m on the shared planes", check.rms_m, s.max_rms_m);
  }
  if (held.translation_ratio > s.max_sigma_ratio || held.sigma_m > s.max_sigma_m) {
    return format(
        "the planes leave translation along %s (from frame) free: sigma %.3g m, %.3g times the best "
        "held direction's (at most %.3g m and %.3g times)",
        vectorText(held.weakest_translation).c_str(), held.sigma_m, held.translation_ratio, s.max_sigma_m,
        s.max_sigma_ratio);
  }
  if (held.rotation_ratio > s.max_sigma_ratio || held.sigma_deg > s.max_sigma_deg) {
    return format(
        "the planes leave rotation about %s (from frame) free: sigma %.3g deg, %.3g times the best "
        "held axis's (at most %.3g deg and %.3g times)",
        vectorText(held.weakest_rotation).c_str(), held.sigma_deg, held.rotation_ratio, s.max_sigma_deg,
        s.max_sigma_ratio);
  }
  return "";
}

FrameRange endFrames(std::size_t end, const std::optional<std::pair<std::size_t, std::size_t>>& given,
                     const LoopCheckSettings& settings, std::size_t count) {
  if (!given) return neighbourhoodFrames(end, settings.neighbourhood_frames, count);
  if (given->first > end || end > given->second || given->second >= count) {
    throw Error("loop check: frames " + std::to_string(given->first) + ".." + std::to_string(given->second) +
                " do not hold frame " + std::to_string(end) + " of " + std::to_string(count));
  }
  return {given->first, given->second};
}

LoopCheck rejected(LoopCheck check, std::string reason) {
  check.accepted = false;
  check.reason = std::move(reason);
  return check;
}

}  // namespace

LoopCheck verifyLoop(const io::ScanSource& scans, const std::vector<Pose>& poses, const LoopPair& pair,
                     const LoopCheckSettings& settings, const std::optional<LoopEnds>& ends) {
  checkInput(scans, poses, pair, settings);
  const Pose guess = pair.relative ? *pair.relative : relative(poses[pair.from], poses[pair.to]);
  LoopCheck check;
  check.relative = guess;

  const FrameRange from_frames =
      endFrames(pair.from, ends ? std::optional(ends->from) : std::nullopt, settings, scans.size());
  const FrameRange to_frames =
      endFrames(pair.to, ends ? std::optional(ends->to) : std::nullopt, settings, scans.size());
  if (from_frames.overlaps(to_frames)) {
    return rejected(check, "the neighbourhoods share frames: one stretch of the path, not a loop");
  }
  const PointCloud from_map =
      mergeNeighbourhood(scans, poses, pair.from, from_frames, settings.neighbourhood_voxel);
  const PointCloud to_map =
      mergeNeighbourhood(scans, poses, pair.to, to_frames, settings.neighbourhood_voxel);
  if (from_map.empty() || to_map.empty()) return rejected(check, "a neighbourhood has no points");

  Pose start = guess;
  if (settings.search_radius_m > 0.0 || settings.search_yaw_deg > 0.0) {
    BirdsEyeSearchSettings search;
    search.radius_m = settings.search_radius_m;
    search.yaw_deg = settings.search_yaw_deg;
    search.cell_m = settings.search_cell_m;
    search.structure_height_m = settings.structure_height_m;
    search.ambiguous_distance_m = settings.ambiguous_distance_m;
    search.ambiguous_yaw_deg = settings.ambiguous_yaw_deg;
    const BirdsEyeMatch match = searchBirdsEye(from_map, to_map, guess, search);
    check.search_score = match.score;
    check.search_second_score = match.second_score;
    if (match.score < settings.min_search_score) {
      return rejected(check,
                      format("coarse search: best score %.2f below %.2f (%zu structure cells): the maps "
                             "do not look alike",
                             match.score, settings.min_search_score, match.structure_cells));
    }
    if (match.second_score >= settings.max_second_peak_ratio * match.score) {
      return rejected(check,
                      format("coarse search: ambiguous, a second peak far from the best scores %.2f of "
                             "its %.2f (a repetitive or corridor-like place)",
                             match.second_score / match.score, match.score));
    }
    start = match.relative;
  }

  const ba::BaResult result =
      ba::optimizeWindow({&from_map, &to_map}, {Pose(), start}, jointWindowSettings(settings));
  check.relative = relative(result.poses[0], result.poses[1]);
  const Pose correction = relative(guess, check.relative);
  check.correction_m = correction.t.norm();
  check.correction_deg = so3Log(correction.q).norm() * 180.0 / M_PI;
  check.shared_planes = result.num_planes;
  if (!result.trusted) {
    return rejected(check, "the joint plane BA made the planes at the start pose blurrier (not trusted)");
  }
  if (result.num_planes == 0) return rejected(check, "no shared planes: the neighbourhoods do not overlap");

  check.rms_m =
      std::sqrt(result.final_cost / static_cast<double>(std::max<std::size_t>(1, result.num_plane_points)));
  voxel::PlaneSettings finest = jointWindowSettings(settings).planes;
  finest.voxel_size = settings.final_voxel_size;
  check.overlap = planeOverlap(to_map, result.plane_point_indices[1], finest);

  check.information =
      graph::relativePoseInformation(result.hessian, result.poses, 0, 1, settings.information);
  const double to_fisher = 1.0 / (2.0 * settings.information.point_sigma * settings.information.point_sigma);
  const HeldDirections held = heldDirections(result.hessian.block<6, 6>(6, 6) * to_fisher);
  check.sigma_m = held.sigma_m;
  check.sigma_deg = held.sigma_deg;

  check.reason = rejection(check, held, settings);
  check.accepted = check.reason.empty();
  return check;
}

}  // namespace hba::closure
