#pragma once
// A short simulated drive held in memory, for the pyramid's library tests.
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/simulation.hpp"

namespace hba::pyramid::test {

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

}  // namespace hba::pyramid::test
