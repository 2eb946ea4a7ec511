#include "hba/sim/simulation.hpp"

#include <algorithm>

#include "hba/core/error.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::sim {

void validate(const SimulationConfig& config) {
  validate(config.sensor);
  validate(config.drift);
  if (!(config.downsample_voxel >= 0.0)) {
    throw Error("simulate: the downsampling voxel must be >= 0 m");
  }
  if (!(config.world.max_slope >= 0.0) || config.world.max_slope > 0.2) {
    throw Error("simulate: the terrain slope must be in [0, 0.2]");
  }
}

Simulation prepareSimulation(const SimulationConfig& config) {
  validate(config);
  Simulation simulation;
  simulation.config = config;
  simulation.terrain = Terrain(config.seed, config.world.max_slope);
  simulation.truth = makeTrajectory(config.trajectory, simulation.terrain);
  simulation.initial = applyDrift(simulation.truth.poses, config.drift, config.seed);
  simulation.world = buildWorld(simulation.truth.poses, simulation.terrain, config.world, config.seed);
  return simulation;
}

PointCloud simulateFrame(const Simulation& simulation, std::size_t frame) {
  const PointCloud cloud = scan(simulation.world, simulation.truth.poses.at(frame), simulation.config.sensor,
                                simulation.config.seed, frame);
  return voxel::downsample(cloud, simulation.config.downsample_voxel);
}

std::string scanFileName(std::size_t frame, std::size_t frames) {
  const std::size_t width = std::max<std::size_t>(6, std::to_string(frames - 1).size());
  std::string digits = std::to_string(frame);
  return std::string(width - std::min(width, digits.size()), '0') + digits + ".pcd";
}

}  // namespace hba::sim
