#pragma once
// A whole synthetic sequence: world, ground-truth path, drifting initial
// poses and one scan per frame, written as an HBA dataset folder:
//
//   DIR/pcd/000000.pcd ...  scans, binary PCD (x y z intensity [time]), sensor frame
//   DIR/pose.json           initial (drifting) poses, HBA format
//   DIR/gt.txt              ground truth, TUM format, stamps index / rate
//   DIR/times.txt           the same stamps, one a line (hba reads them with the poses)
//   DIR/sim.yaml            every parameter, the seed and the hba version
//
// Output is bit-identical for a seed whatever the number of threads: each
// frame draws from its own generator seeded by (seed, frame).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/drift.hpp"
#include "hba/sim/sensor.hpp"
#include "hba/sim/terrain.hpp"
#include "hba/sim/trajectory.hpp"
#include "hba/sim/world.hpp"

namespace hba::sim {

struct SimulationConfig {
  std::uint64_t seed = 1;
  TrajectoryConfig trajectory;
  SensorConfig sensor = sensorPreset(SensorModel::Vlp16);
  Scene scene = Scene::Mixed;  // the preset `world` was made from (for sim.yaml)
  WorldConfig world;
  DriftConfig drift;
  double downsample_voxel = 0.0;  // m; 0 keeps every return
  // Raw sweeps: each frame's rays fire over the frame's interval from the
  // moving sensor, and the scans carry every point's time since the frame's
  // stamp (PCD field "time", s). Off: as if deskewed.
  bool sweep = false;
};

// Everything but the scans, computed once up front.
struct Simulation {
  SimulationConfig config;
  Terrain terrain{0, 0.0};
  Trajectory truth;           // sensor poses, with stamps
  std::vector<Pose> initial;  // drifted (or loop-closed noisy) poses
  World world;
};

// Throws hba::Error on invalid settings (the trajectory's are checked when it is made).
void validate(const SimulationConfig& config);
// Throws hba::Error on invalid settings.
Simulation prepareSimulation(const SimulationConfig& config);
// Scan of one frame (downsampled if configured). Thread-safe.
PointCloud simulateFrame(const Simulation& simulation, std::size_t frame);

// Called with (frames done, frames total) every `progress_every` frames and at
// the end, from worker threads but never concurrently.
using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

struct WriteOptions {
  bool force = false;  // replace a non-empty output folder
  // pose.json, gt.txt and sim.yaml only, no pcd/: the scans depend on neither
  // the drift model nor its rates, so one set of scans serves several.
  bool poses_only = false;
  std::size_t progress_every = 100;
  ProgressCallback progress;
};

// Writes the dataset into `output` (without pcd/ if `poses_only`). Refuses a non-empty existing folder
// unless `force`. Everything is written into a hidden staging folder beside
// `output` that is renamed into place only when complete, so a killed run
// never leaves a dataset that looks finished. Throws hba::Error.
void writeSimulation(const Simulation& simulation, const std::filesystem::path& output,
                     const WriteOptions& options);

// File name of frame `frame` among `frames`: zero-padded to at least 6 digits.
std::string scanFileName(std::size_t frame, std::size_t frames);
// Writes sim.yaml (parameters and a few statistics).
void writeSimulationYaml(const Simulation& simulation, const std::filesystem::path& path);

}  // namespace hba::sim
