#pragma once
// Initial poses for the optimizer: the ground truth corrupted the way
// LiDAR odometry corrupts it.
//
// Drift (default): the relative motion between consecutive frames is
// perturbed and the poses are re-integrated, so errors accumulate and loops
// open. Per metre driven, the translation gains an error of
// `translation` x distance (along a body-frame direction that wanders slowly),
// the heading turns by `rotation_deg_per_m` (a yaw bias whose sign wanders
// over hundreds of metres, plus a tenth of it in roll/pitch), and the height
// drifts by `vertical` x distance (odometry drifts in z too).
//
// Loop-closed: each pose gets small independent noise only, like the output
// of a SLAM system that has already closed its loops.
#include <cstdint>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::sim {

struct DriftConfig {
  double translation = 0.01;         // m of error per m driven (1 %)
  double rotation_deg_per_m = 0.01;  // deg of heading error per m driven
  double vertical = 0.002;           // m of height error per m driven
  double wander_length = 300.0;      // m over which the drift directions decorrelate
  bool loop_closed = false;
  double closed_translation_sigma = 0.03;  // m, per axis
  double closed_rotation_sigma_deg = 0.1;  // deg, per axis
  // Per-frame errors on top of the drift, independent from frame to frame,
  // as real odometry has them (registration noise, deskew residuals, z and
  // attitude wobble): sigma per axis. 0 = smooth drift only.
  double jitter_translation = 0.0;   // m
  double jitter_rotation_deg = 0.0;  // deg
};

// Throws hba::Error for negative rates or sigmas.
void validate(const DriftConfig& config);
// Deterministic for a seed. The first pose is kept exact (it fixes the frame).
std::vector<Pose> applyDrift(const std::vector<Pose>& truth, const DriftConfig& config, std::uint64_t seed);

}  // namespace hba::sim
