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
  if (config.sweep && config.downsample_voxel > 0.0) {
    throw Error("simulate: raw sweeps keep every point with its time: --downsample does not apply to them");
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
  if (simulation.config.sweep) {
    const Trajectory& truth = simulation.truth;
    const double start = truth.stamps.at(frame);
    const std::vector<Return> returns = sweepReturns(
        simulation.world, [&truth, start](double t) { return poseAtTime(truth, start + t); },
        1.0 / simulation.config.trajectory.frame_rate_hz, simulation.config.sensor, simulation.config.seed,
        frame);
    PointCloud cloud;
    cloud.reserve(returns.size(), true);
    cloud.time.reserve(returns.size());
    for (const Return& r : returns) {
      cloud.add(r.point.cast<float>(), r.intensity);
      cloud.time.push_back(r.time);
    }
    return cloud;
  }
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
