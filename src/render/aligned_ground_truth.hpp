#pragma once
// Ground truth drawn over a result (private to render): it may live in
// another frame, so it is moved rigidly onto the result first.
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/eval/alignment.hpp"

namespace hba::render {

// Ground truth moved onto `reference` when both pair up by index; as given otherwise.
inline std::vector<Pose> alignedGroundTruth(const std::vector<Pose>& ground_truth,
                                            const std::vector<Pose>& reference) {
  if (ground_truth.size() != reference.size() || ground_truth.size() < 3) return ground_truth;
  const eval::Similarity s = eval::alignTrajectory(reference, ground_truth, eval::Alignment::SE3);
  std::vector<Pose> out;
  out.reserve(ground_truth.size());
  for (const Pose& p : ground_truth) out.push_back(s.apply(p));
  return out;
}

}  // namespace hba::render
