#pragma once
// Before a long run: do the poses and scans follow hba's convention
// (sensor-to-world poses, sensor-frame scans)? A few stretches of the
// sequence are merged in several ways: with the poses as given, with each
// pose inverted (world-to-sensor poses), without poses (scans saved in the
// world frame already), and with the poses of a body whose axes are turned
// against the sensor's by each of the 23 other axis-aligned rotations (an
// IMU mounted turned, Ouster's sensor vs LiDAR frame, KITTI's camera-0 poses
// without their calibration). Whichever occupies the fewest voxels is the crisper
// map; a clear winner other than "as given" means the input is in another
// convention, and the user is told which flag fixes it.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::pipeline {

enum class ConventionVerdict {
  AsGiven,          // the poses as given make the crispest map (or nothing tells)
  PosesInverted,    // inverting every pose makes a clearly crisper map
  ScansInWorld,     // the scans line up without any pose
  TurnedBody,       // the poses are of a body turned against the sensor (`turn`)
  ScansNotInWorld,  // --scans-in-world was given, but the scans as stored line up
};

// The convention flags the user gave, so the advice can undo them.
struct GivenConventions {
  bool invert_poses = false;
  bool scans_in_world = false;
  bool extrinsic = false;  // --extrinsic or a KITTI calibration
};

struct ConventionCheck {
  ConventionVerdict verdict = ConventionVerdict::AsGiven;
  // Occupied voxels of the merged stretches per candidate, relative to the
  // mean occupancy of one scan (lower = crisper).
  double as_given = 0.0, inverted = 0.0, in_world = 0.0;
  double turned = 0.0;           // the best of the 23 turned bodies
  double as_stored = 0.0;        // with --scans-in-world undone (0 unless it was given)
  Mat3 turn = Mat3::Identity();  // its rotation T_body_sensor
  std::size_t stretches = 0;     // stretches with enough motion to tell; 0: nothing checked
  std::string message;           // what is wrong and which flag fixes it (empty when AsGiven)
  // Why the stretches could not tell the conventions apart (scans of too few
  // points), when they could not: the verdict is then AsGiven.
  std::string cannot_tell;
};

struct ConventionSettings {
  double voxel = 0.5;            // m
  double stretch_length = 10.0;  // m of path per stretch (or the rotation below)
  double stretch_rotation_deg = 45.0;
  std::size_t stretch_scans = 8;  // scans merged per stretch
  std::size_t max_stretches = 4;
  double decisive_ratio = 0.7;  // another candidate needs at most this share of the voxels
  // Scans occupying fewer voxels than this (on average) tell nothing: a scan
  // of one point fills one voxel however it is moved, so scans merged without
  // poses always look crisper than spread along the path.
  double min_scan_voxels = 20.0;
};

// Reads at most max_stretches * stretch_scans scans. Throws what the source throws.
ConventionCheck checkConventions(const io::ScanSource& scans, const std::vector<Pose>& poses,
                                 const GivenConventions& given = {}, const ConventionSettings& settings = {});

}  // namespace hba::pipeline
