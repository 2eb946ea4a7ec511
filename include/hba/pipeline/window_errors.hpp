#pragma once
// Where error enters the pyramid, measured against a reference trajectory
// (a simulation's truth, or a trusted map's poses): for every window of
// every layer, the relative pose of each of its frames from its first,
// P_0^-1 P_k, compared with the reference's, Q_0^-1 Q_k, as the window
// began, as its BA left it, and in the input, the hierarchy's and the
// final poses. A layer whose windows come out further from the reference
// than they began adds error; one whose final poses are further than its
// windows loses what its windows found in the top-down step.
#include <array>
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/pipeline/report.hpp"

namespace hba::pipeline {

// RMS over frame pairs of the relative pose error, by axis of the pair's
// first frame: rotation about x, y, z (roll, pitch, yaw for a sensor with
// x forward and z up; degrees) and translation along x, y, z (m). The
// error of a pair: rotation log(R_P R_Q^T) and translation t_P - t_Q, of
// the relative poses P (estimate) and Q (reference).
struct RelativeErrorRms {
  std::array<double, 3> rotation_deg{0.0, 0.0, 0.0};
  std::array<double, 3> translation_m{0.0, 0.0, 0.0};
  double rotation_rms_deg = 0.0;  // of the angle, over all axes
  double translation_rms_m = 0.0;
};

struct LayerWindowErrors {
  int iteration = 0;
  int layer = 0;
  bool global = false;
  std::size_t windows = 0;
  std::size_t pairs = 0;       // frames that are not their window's first
  RelativeErrorRms input;      // the input poses
  RelativeErrorRms start;      // the windows' poses as they began
  RelativeErrorRms window;     // as the windows' BAs left them
  RelativeErrorRms hierarchy;  // the hierarchy's result (top-down pose graph)
  RelativeErrorRms final;      // the run's output
};

// One row per layer and round, in the order of `records`. `input`,
// `hierarchy`, `final` and `reference` are layer-1 poses, one per scan;
// only relative poses are compared, so any frames will do. Throws
// hba::Error if their counts differ or a record names a scan beyond them.
std::vector<LayerWindowErrors> windowErrors(const std::vector<WindowRecord>& records,
                                            const std::vector<Pose>& input,
                                            const std::vector<Pose>& hierarchy,
                                            const std::vector<Pose>& final,
                                            const std::vector<Pose>& reference);

}  // namespace hba::pipeline
