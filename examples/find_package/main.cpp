// Optimizes a small simulated drive with the installed library and prints
// how far the poses were from the truth before and after; exit 0 when the
// result is closer.
#include <hba/hba.hpp>

#include <iostream>

namespace {

double meanError(const std::vector<hba::Pose>& truth, const std::vector<hba::Pose>& poses) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    sum += (hba::relative(truth.front(), truth[i]).t - hba::relative(poses.front(), poses[i]).t).norm();
  }
  return sum / static_cast<double>(poses.size());
}

}  // namespace

int main() {
  hba::sim::SimulationConfig config;
  config.seed = 5;
  config.trajectory.frames = 30;
  config.sensor = hba::sim::sensorPreset(hba::sim::SensorModel::Livox);
  config.drift.translation = 0.03;
  const hba::sim::Simulation simulation = hba::sim::prepareSimulation(config);
  std::vector<hba::PointCloud> scans;
  for (std::size_t i = 0; i < simulation.initial.size(); ++i)
    scans.push_back(hba::sim::simulateFrame(simulation, i));

  const hba::io::MemoryScanSource source(std::move(scans));
  const hba::pipeline::HbaResult result =
      hba::pipeline::runHierarchicalBa(source, simulation.initial, hba::HbaSettings());

  const double before = meanError(simulation.truth.poses, simulation.initial);
  const double after = meanError(simulation.truth.poses, result.poses);
  std::cout << "hba " << HBA_VERSION << ": mean position error " << before * 1000 << " mm -> " << after * 1000
            << " mm\n";
  return after < before ? 0 : 1;
}
