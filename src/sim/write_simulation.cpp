// Writing a simulated sequence: scans in parallel, then the pose files.
#include "core/staging_folder.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/simulation.hpp"
#include "scan_writer.hpp"

namespace hba::sim {
namespace fs = std::filesystem;

namespace {

// The small files last: even inside the staging folder, a dataset without
// pose.json does not look complete.
void writePoseFiles(const Simulation& simulation, const fs::path& dir) {
  io::writePoses(dir / "gt.txt", simulation.truth, io::PoseFormat::Tum);
  io::writeTimes(dir / "times.txt", simulation.truth.stamps);
  writeSimulationYaml(simulation, dir / "sim.yaml");
  Trajectory initial;
  initial.poses = simulation.initial;
  initial.stamps = simulation.truth.stamps;
  io::writePoses(dir / "pose.json", initial, io::PoseFormat::Hba);
}

}  // namespace

void writeSimulation(const Simulation& simulation, const fs::path& output, const WriteOptions& options) {
  StagingFolder staging(output, options.force);
  if (!options.poses_only) {
    writeScans(
        simulation.truth.size(), [&](std::size_t k) { return simulateFrame(simulation, k); },
        staging.path() / "pcd", options);
  }
  writePoseFiles(simulation, staging.path());
  staging.commit();
}

}  // namespace hba::sim
