#pragma once
// A synthetic BA window for tests and benchmarks: square plane patches with
// varied normals (so every pose direction is observable), each sampled by
// every frame, with true and perturbed poses.
#include <cstdint>
#include <vector>

#include "hba/ba/window_ba.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::test {

struct SyntheticWindowSpec {
  int frames = 5;
  int points_per_patch = 80;       // per frame and patch
  double noise_sigma = 0.0;        // along the patch normal (m)
  double patch_size = 6.0;         // edge of each square patch (m)
  double grid = 8.0;               // patches sit at centres of this grid's cells
  double perturb_angle_deg = 1.0;  // per-frame error of the initial poses
  double perturb_translation = 0.2;
  std::uint32_t seed = 1;
};

struct SyntheticWindow {
  std::vector<PointCloud> scans;  // sensor frame
  std::vector<Pose> truth;
  std::vector<Pose> initial;  // truth with each frame perturbed
  std::vector<const PointCloud*> scanPointers() const;
};

SyntheticWindow makeSyntheticWindow(const SyntheticWindowSpec& spec);

// BA settings that take each patch as one plane: the grid's cell as the root
// voxel and one voxel size for every association (coarse to fine would cut
// the patches), three associations.
ba::BaSettings patchBaSettings(const SyntheticWindowSpec& spec = {});

// Rotation (deg) and translation (m) error of frame i relative to frame 0,
// compared with the same relative pose of `truth`: the BA gauge.
struct RelativeError {
  double max_angle_deg = 0.0;
  double max_translation = 0.0;
};
RelativeError relativePoseError(const std::vector<Pose>& estimate, const std::vector<Pose>& truth);

}  // namespace hba::test
