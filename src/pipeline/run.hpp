#pragma once
// What the stages of one run of the method share (hierarchical_ba.cpp): its
// inputs, the poses as they pass from stage to stage, what a stage found
// that a later one acts on, and the report (which no stage reads).
#include <string>
#include <utility>
#include <vector>

#include "closure_stage.hpp"
#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "pyramid/timed_clouds.hpp"

namespace hba::pipeline {

struct Run {
  Run(const pyramid::TimedClouds& scans_in, const HbaSettings& settings_in, const dist::Group& group_in)
      : scans(scans_in), settings(settings_in), group(group_in) {}

  const pyramid::TimedClouds& scans;  // layer 1: every scan read and downsampled once
  const HbaSettings& settings;        // resolved: window size and threads chosen
  const dist::Group& group;           // the processes of an mpirun (one, usually)
  ClosureInputs closures;             // loops and priors to close, in the frame of `input`
  // World points are floats: 4000 km from the origin (UTM) they are 0.25 m
  // apart. The stages work near the first input pose (`origin`), and after
  // the closure stage near its start's first pose (`origin + shift`).
  Vec3 origin = Vec3::Zero();
  Vec3 shift = Vec3::Zero();
  std::vector<Pose> input;      // the input poses, near the origin
  ClosureOutcome closed;        // the closure stage's start, loops and priors
  std::vector<Pose> poses;      // the current poses, handed from stage to stage
  std::vector<Pose> hierarchy;  // the pyramid's result, before the refinement
  int layers = 0;               // the pyramid's layers, planned from the frame count
  // Found by the pyramid stage: the points layer 1 held (its first round),
  // the planes of every layer and round (none: the input is returned).
  std::size_t layer_one_points = 0;
  std::size_t planes_found = 0;
  // Found by the refinement: nothing was gained from the start (a converged
  // input), and the priors held by its blocks to the end (no pass after them
  // moved the frames without the priors), so no re-anchoring is due.
  bool converged_at_start = false;
  bool priors_held = false;
  HbaReport report;
  // Each stage run so far, in order, and its wall time (s).
  std::vector<std::pair<std::string, double>> stage_seconds;
};

}  // namespace hba::pipeline
