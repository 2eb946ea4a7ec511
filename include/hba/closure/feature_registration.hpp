#pragma once
// Global registration of two clouds of one place from any start: descriptor
// matches (mutual nearest FPFH), a robust estimate from them (RANSAC over
// triples whose side lengths agree in both clouds), then point-to-plane ICP.
// Assumes nothing of the relative pose: not z up, not a small offset.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hba/closure/point_features.hpp"
#include "hba/core/pose.hpp"

namespace hba::closure {

struct RegistrationSettings {
  double inlier_voxels = 1.5;         // a match agrees with a pose within this many voxels
  double edge_similarity = 0.9;       // a triple's sides in both clouds: shorter/longer at least this
  std::size_t max_draws = 60000;      // random triples drawn
  std::size_t max_hypotheses = 3000;  // triples that pass the side test and are scored, at most
  std::size_t min_inliers = 10;       // fewer matches agreeing on the best pose: not found
  std::size_t icp_iterations = 20;
  double icp_reach_voxels = 2.0;  // a point pairs with the nearest target within this many voxels
  std::uint32_t seed = 20231;     // fixed: results repeat
};

struct Registration {
  bool found = false;
  Pose target_from_source;  // maps the source cloud into the target's frame
  std::size_t matches = 0;  // mutual descriptor matches
  std::size_t inliers = 0;  // of them, agreeing with the robust estimate
  double fitness = 0.0;     // share of the source's points on the target's surfaces after ICP
  double rms_m = 0.0;       // their point-to-plane RMS
  std::string reason;       // why not found
};

// Deterministic; single-threaded (callers register many pairs in parallel).
Registration registerClouds(const FeatureCloud& source, const FeatureCloud& target,
                            const RegistrationSettings& settings = {});

// The keypoints whose descriptors are each other's nearest: pairs of point
// indices (source, target).
std::vector<std::pair<std::uint32_t, std::uint32_t>> mutualMatches(const FeatureCloud& source,
                                                                   const FeatureCloud& target);

}  // namespace hba::closure
