#include "hba/eval/trajectory_error.hpp"

#include <cmath>

#include "hba/core/error.hpp"

namespace hba::eval {

double rotationAngleDeg(const Quat& q) {
  // atan2 of the half-angle stays accurate near 0, where acos((tr R - 1)/2) does not.
  const Quat n = q.normalized();
  const double half = std::atan2(n.vec().norm(), std::abs(n.w()));
  return 2.0 * half * 180.0 / M_PI;
}

namespace {

void addError(const Pose& error, std::vector<double>& translation, std::vector<double>& rotation) {
  translation.push_back(error.t.norm());
  rotation.push_back(rotationAngleDeg(error.q));
}

}  // namespace

PoseErrors absoluteErrors(const std::vector<Pose>& reference, const std::vector<Pose>& estimate) {
  if (reference.size() != estimate.size()) throw Error("ATE: sequences differ in length");
  std::vector<double> translation, rotation;
  translation.reserve(reference.size());
  rotation.reserve(reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    // E = Q^-1 P: its translation has the norm of t_P - t_Q.
    addError(relative(reference[i], estimate[i]), translation, rotation);
  }
  return {summarize(std::move(translation)), summarize(std::move(rotation))};
}

std::vector<std::pair<std::size_t, std::size_t>> rpePairs(const std::vector<Pose>& reference, double delta,
                                                          DeltaUnit unit) {
  if (!(delta > 0.0)) throw Error("RPE delta must be > 0");
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  const std::size_t n = reference.size();
  if (unit == DeltaUnit::Frames) {
    const double rounded = std::round(delta);
    if (std::abs(rounded - delta) > 1e-9) throw Error("RPE delta in frames must be an integer");
    const auto step = static_cast<std::size_t>(rounded);
    for (std::size_t i = 0; i + step < n; ++i) pairs.emplace_back(i, i + step);
    return pairs;
  }
  std::vector<double> distance(n, 0.0);  // path length from pose 0
  for (std::size_t i = 1; i < n; ++i) {
    distance[i] = distance[i - 1] + (reference[i].t - reference[i - 1].t).norm();
  }
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i + 1);
    while (j < n && distance[j] - distance[i] < delta) ++j;
    if (j >= n) break;  // later starts reach even less far
    pairs.emplace_back(i, j);
  }
  return pairs;
}

PoseErrors relativeErrors(const std::vector<Pose>& reference, const std::vector<Pose>& estimate,
                          const std::vector<std::pair<std::size_t, std::size_t>>& pairs) {
  if (reference.size() != estimate.size()) throw Error("RPE: sequences differ in length");
  std::vector<double> translation, rotation;
  translation.reserve(pairs.size());
  rotation.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    const Pose reference_motion = relative(reference.at(i), reference.at(j));
    const Pose estimated_motion = relative(estimate.at(i), estimate.at(j));
    addError(relative(reference_motion, estimated_motion), translation, rotation);
  }
  return {summarize(std::move(translation)), summarize(std::move(rotation))};
}

TrajectoryEvaluation evaluateTrajectory(const Trajectory& reference, const Trajectory& estimate,
                                        const EvalOptions& options) {
  if (reference.empty()) throw Error("the reference trajectory is empty");
  if (estimate.empty()) throw Error("the estimated trajectory is empty");
  TrajectoryEvaluation result;
  result.reference_count = reference.size();
  result.estimate_count = estimate.size();

  const Association pairs = associate(reference, estimate, options.association, options.max_time_diff);
  result.association_used = pairs.mode;
  result.matched = pairs.size();

  std::vector<Pose> matched_reference, matched_estimate;
  matched_reference.reserve(pairs.size());
  matched_estimate.reserve(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    matched_reference.push_back(reference.poses[pairs.reference[k]]);
    matched_estimate.push_back(estimate.poses[pairs.estimate[k]]);
  }

  result.alignment = alignTrajectory(matched_reference, matched_estimate, options.alignment);
  for (Pose& p : matched_estimate) p = result.alignment.apply(p);

  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::size_t i = pairs.estimate[k];
    result.pose_times.push_back(estimate.hasStamps() ? estimate.stamps[i] : static_cast<double>(i));
    addError(relative(matched_reference[k], matched_estimate[k]), result.ate_translation_m,
             result.ate_rotation_deg);
  }
  result.ate = {summarize(result.ate_translation_m), summarize(result.ate_rotation_deg)};
  result.rpe = relativeErrors(matched_reference, matched_estimate,
                              rpePairs(matched_reference, options.rpe_delta, options.rpe_unit));
  return result;
}

}  // namespace hba::eval
