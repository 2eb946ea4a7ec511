#pragma once
// A small simulated scene shared by the sim tests (built once per process).
#include "hba/sim/simulation.hpp"

namespace hba::sim::test {

// A 120-frame city-block tour with a VLP-16 and noise/dropout switched off.
inline const Simulation& smallSimulation() {
  static const Simulation simulation = [] {
    SimulationConfig config;
    config.seed = 3;
    config.trajectory.frames = 120;
    config.sensor.range_noise = 0.0;
    config.sensor.dropout = 0.0;
    return prepareSimulation(config);
  }();
  return simulation;
}

}  // namespace hba::sim::test
