#pragma once
// Absolute and relative trajectory errors, with the definitions of the `evo`
// tool (docs/eval.md gives the formulas):
//  - ATE (evo's APE): after aligning the estimate, per matched pose the
//    translation error |t_ref - t_est| (m) and the rotation error, the angle
//    of R_ref^-1 R_est (degrees).
//  - RPE: for pose pairs (i, j) a fixed number of frames or metres apart, the
//    error of the relative motion E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), Q the
//    reference and P the estimate: |trans(E)| (m) and angle(rot(E)) (deg).
#include <cstddef>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/eval/alignment.hpp"
#include "hba/eval/association.hpp"
#include "hba/eval/error_stats.hpp"

namespace hba::eval {

enum class DeltaUnit { Frames, Meters };

struct PoseErrors {
  ErrorStats translation_m;
  ErrorStats rotation_deg;
};

// Rotation angle of R in degrees, in [0, 180].
double rotationAngleDeg(const Quat& q);

// Per-pose ATE of already associated and aligned sequences (same length).
PoseErrors absoluteErrors(const std::vector<Pose>& reference, const std::vector<Pose>& estimate);

// Index pairs (i, j), one for every start i: j = i + delta for frames; for
// metres the first j whose reference path length from i reaches delta.
std::vector<std::pair<std::size_t, std::size_t>> rpePairs(const std::vector<Pose>& reference, double delta,
                                                          DeltaUnit unit);
// Per-pair RPE of associated sequences over the given pairs.
PoseErrors relativeErrors(const std::vector<Pose>& reference, const std::vector<Pose>& estimate,
                          const std::vector<std::pair<std::size_t, std::size_t>>& pairs);

struct EvalOptions {
  Alignment alignment = Alignment::SE3;
  AssociationMode association = AssociationMode::Auto;
  double max_time_diff = 0.01;  // s, for time association
  double rpe_delta = 1.0;
  DeltaUnit rpe_unit = DeltaUnit::Frames;
};

struct TrajectoryEvaluation {
  std::size_t reference_count = 0;
  std::size_t estimate_count = 0;
  std::size_t matched = 0;
  AssociationMode association_used = AssociationMode::Index;
  Similarity alignment;  // maps the estimate onto the reference
  PoseErrors ate;
  PoseErrors rpe;
  // Per matched pose, in the estimate's order: its time (the estimate's
  // stamp, else its index) and its ATE, for plots over time.
  std::vector<double> pose_times;
  std::vector<double> ate_translation_m, ate_rotation_deg;
};

// Associates, aligns (the RPE uses the aligned estimate too, which matters
// only for the scale of Sim(3)), then computes ATE and RPE. Throws hba::Error.
TrajectoryEvaluation evaluateTrajectory(const Trajectory& reference, const Trajectory& estimate,
                                        const EvalOptions& options = {});

}  // namespace hba::eval

namespace hba {
template <>
struct EnumNames<eval::DeltaUnit> {
  static constexpr const char* what = "delta unit";
  static constexpr EnumName<eval::DeltaUnit> names[] = {{eval::DeltaUnit::Frames, "frames"},
                                                        {eval::DeltaUnit::Meters, "m"}};
};
}  // namespace hba
