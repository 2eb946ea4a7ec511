// Writing a simulated sequence: scans in parallel, then the pose files.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <mutex>

#include "hba/core/progress.hpp"
#include "hba/core/staging_folder.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/simulation.hpp"

namespace hba::sim {
namespace fs = std::filesystem;

namespace {

void writeScans(const Simulation& simulation, const fs::path& scans, const WriteOptions& options) {
  fs::create_directory(scans);
  const std::size_t frames = simulation.truth.size();
  std::atomic<std::size_t> done{0};
  Progress progress("simulating", frames, "frames");
  std::mutex progress_mutex;
  // One frame per task: frames cost milliseconds each, so scheduling is free,
  // and each frame's output depends only on (seed, frame).
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, frames, 1), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          io::writePcd(scans / scanFileName(k, frames), simulateFrame(simulation, k),
                       io::PcdEncoding::Binary);
          const std::size_t finished = ++done;
          progress.advance();
          const bool report =
              options.progress && options.progress_every > 0 && finished % options.progress_every == 0;
          if (report) {
            const std::lock_guard<std::mutex> lock(progress_mutex);
            options.progress(finished, frames);
          }
        }
      });
  if (options.progress && (options.progress_every == 0 || frames % options.progress_every != 0)) {
    options.progress(frames, frames);
  }
}

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
  if (!options.poses_only) writeScans(simulation, staging.path() / "pcd", options);
  writePoseFiles(simulation, staging.path());
  staging.commit();
}

}  // namespace hba::sim
