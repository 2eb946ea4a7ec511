#pragma once
// A short simulated drive held in memory, for the pyramid's library tests.
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/simulation.hpp"

namespace hba::test {

struct Sequence {
  std::vector<PointCloud> scans;
  Trajectory truth;
  std::vector<Pose> initial;
};

// Every frame of `config`, simulated at once.
inline Sequence simulateSequence(const sim::SimulationConfig& config) {
  const sim::Simulation simulation = sim::prepareSimulation(config);
  Sequence s;
  for (std::size_t i = 0; i < config.trajectory.frames; ++i) {
    s.scans.push_back(sim::simulateFrame(simulation, i));
  }
  s.truth = simulation.truth;
  s.initial = simulation.initial;
  return s;
}

// A drive of `frames` frames with a small solid-state sensor (small scans,
// fast tests) and drifting odometry.
inline sim::SimulationConfig smallDriveConfig(std::size_t frames) {
  sim::SimulationConfig config;
  config.seed = 11;
  config.trajectory.frames = frames;
  config.sensor = sim::sensorPreset(sim::SensorModel::Livox);
  config.drift.translation = 0.03;
  config.drift.rotation_deg_per_m = 0.05;
  return config;
}

}  // namespace hba::test
