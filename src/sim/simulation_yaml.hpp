#pragma once
// The parts of sim.yaml, shared by one sequence and each session of several
// (whose sim.yaml adds its files and a `session` section).
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "hba/sim/simulation.hpp"

namespace hba::sim {

// generator, version, seed.
void emitYamlHeader(YAML::Emitter& out, std::uint64_t seed);
// The entries of `files` every dataset folder has (inside an open map).
void emitDatasetFiles(YAML::Emitter& out);
// sensor_frame, trajectory, sensor, downsampling, world, initial_poses.
void emitYamlBody(YAML::Emitter& out, const SimulationConfig& config, const std::vector<Pose>& truth,
                  const World& world);
void writeYamlFile(const std::filesystem::path& path, const YAML::Emitter& out);

}  // namespace hba::sim
