#pragma once
// A tiny synthetic sequence for command-line tests: a floor (z = 0, x in
// [-1, 6], y in [-4, 4]) and a wall (x = 5, y in [-3, 3], z in [0, 2]) seen
// from a few poses, written in the "scans" layout (Scans/NNNNNN.pcd +
// odom_poses.txt, KITTI). Every scan holds the whole scene in its sensor
// frame, so the exact poses give a crisp map.
#include <filesystem>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::test {

std::vector<Pose> syntheticPoses();
// The scans (sensor frame) of the scene seen from `poses`, as the dataset holds them.
std::vector<PointCloud> syntheticScans(const std::vector<Pose>& poses);
// Writes the dataset into `dir` with `poses` (one per scan of syntheticPoses()).
void writeSyntheticDataset(const std::filesystem::path& dir, const std::vector<Pose>& poses);

}  // namespace hba::test
