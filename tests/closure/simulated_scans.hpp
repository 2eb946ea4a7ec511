#pragma once
// Scans for the closure tests: a simulated drive whose frames are simulated
// only when a test loads them (a loop check reads a few dozen of hundreds),
// and hand-made scans of a made-up world (a flat field, a corridor).
#include <map>
#include <mutex>
#include <random>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/sim/simulation.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::closure::test {

// Frames of a simulation, simulated on first load and downsampled to layer-1 scans.
class LazySimulatedScans : public io::ScanSource {
 public:
  LazySimulatedScans(const sim::Simulation& simulation, double voxel)
      : simulation_(simulation), voxel_(voxel) {}
  std::size_t size() const override { return simulation_.truth.size(); }
  PointCloud load(std::size_t i) const override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = cache_.find(i);
      if (it != cache_.end()) return it->second;
    }
    PointCloud cloud = voxel::downsample(sim::simulateFrame(simulation_, i), voxel_);
    const std::lock_guard<std::mutex> lock(mutex_);
    return cache_.emplace(i, std::move(cloud)).first->second;
  }

 private:
  const sim::Simulation& simulation_;
  double voxel_;
  mutable std::mutex mutex_;
  mutable std::map<std::size_t, PointCloud> cache_;
};

// A city-block tour of 230 frames (0.5 m apart) whose lap is 200 frames:
// frame k and frame k + 200 see the same place. Odometry drifts by about
// half a metre and a degree over the lap.
inline sim::SimulationConfig revisitingDrive(sim::SensorModel sensor) {
  sim::SimulationConfig config;
  config.seed = 7;
  config.trajectory.shape = sim::PathShape::Block;
  config.trajectory.frames = 230;
  config.sensor = sim::sensorPreset(sensor);
  config.drift.translation = 0.005;
  config.drift.rotation_deg_per_m = 0.01;
  return config;
}

constexpr std::size_t kLap = 200;

// `world` points (with 1 cm noise) within `range` (m, horizontally) of
// poses[k], in that sensor's frame: one scan a pose.
inline std::vector<PointCloud> handMadeScans(const std::vector<Pose>& poses, const std::vector<Vec3>& world,
                                             double range) {
  std::vector<PointCloud> scans;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    std::mt19937 rng(static_cast<unsigned>(k + 1));
    std::normal_distribution<double> noise(0.0, 0.01);
    const Pose to_sensor = poses[k].inverse();
    PointCloud cloud;
    for (const Vec3& p : world) {
      if ((p - poses[k].t).head<2>().norm() > range) continue;
      const Vec3 q = to_sensor * (p + Vec3(noise(rng), noise(rng), noise(rng)));
      cloud.add(q.cast<float>());
    }
    scans.push_back(std::move(cloud));
  }
  return scans;
}

}  // namespace hba::closure::test
