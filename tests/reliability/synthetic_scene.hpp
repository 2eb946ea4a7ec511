#pragma once
// Tiny synthetic datasets (HBA layout: pcd/<i>.pcd + pose.json) for the CLI
// tests of degenerate input: a few scans of a few thousand points, so each
// `hba optimize` run takes well under a second.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::test {

// Samples world points seen from a sensor at `position` (one scan's worth).
using SceneSampler = std::function<std::vector<Vec3>(const Vec3& position, std::uint64_t seed)>;

// A closed 12 x 12 x 4 m room: floor, ceiling, four walls. Fully constrained.
SceneSampler roomScene(std::size_t points_per_scan = 2000);
// An endless 3 m wide corridor along x: walls, floor, ceiling. Nothing
// constrains a translation along x.
SceneSampler corridorScene(std::size_t points_per_scan = 2000);
// Points scattered uniformly in a ball: no plane anywhere.
SceneSampler featurelessScene(std::size_t points_per_scan = 2000);

// `count` poses 0.4 m apart along x with a slow yaw.
std::vector<Pose> straightPath(std::size_t count);
// Each pose moved by a random ~`metres` translation and ~`degrees` rotation.
std::vector<Pose> perturbed(const std::vector<Pose>& poses, double metres, double degrees,
                            std::uint64_t seed);

// Scan i is the scene sampled at truth[i], expressed in the sensor frame of
// truth[i] with 1 cm noise; pose.json holds `initial`.
void writeSceneDataset(const std::filesystem::path& dir, const SceneSampler& scene,
                       const std::vector<Pose>& truth, const std::vector<Pose>& initial);
// Writes pose.json only (for hand-made pose files, use test::writeText).
void writeHbaPoses(const std::filesystem::path& dir, const std::vector<Pose>& poses);

}  // namespace hba::test
