#pragma once
// Simulated LiDARs that measure a World by ray casting.
//
// Points are in the sensor frame (x forward, y left, z up). By default every
// ray of a scan is cast from the one pose of the frame: there is no motion
// distortion, as if the scans had been deskewed. A raw sweep instead casts
// each ray from where the moving sensor is when it fires and keeps the
// point in that instant's sensor frame, with its time. Range noise is Gaussian along the ray;
// dropout removes a ray's return at random; returns closer than min_range
// (the vehicle itself) or farther than max_range are lost.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/world.hpp"

namespace hba::sim {

// Spinning presets resemble Velodyne VLP-16, HDL-32E, HDL-64E and Ouster
// OS-128 (channels spread evenly over the vertical field of view); Livox is a
// forward-looking solid-state sensor with a non-repetitive rosette.
enum class SensorModel { Vlp16, Hdl32, Hdl64, Os128, Livox };

struct SensorConfig {
  SensorModel model = SensorModel::Vlp16;
  // Spinning sensors.
  int channels = 16;
  double min_elevation_deg = -15.0;
  double max_elevation_deg = 15.0;
  int columns = 1800;  // firings per revolution (horizontal resolution 360/columns deg)
  // Rosette sensors.
  int points_per_frame = 24000;
  double field_of_view_deg = 70.4;  // full cone angle
  // Both.
  double min_range = 0.5;     // m
  double max_range = 100.0;   // m
  double range_noise = 0.02;  // m, standard deviation
  double dropout = 0.02;      // probability that a return is lost

  // Rays a frame casts.
  std::size_t raysPerFrame() const;
};

SensorConfig sensorPreset(SensorModel model);
// Throws hba::Error for out-of-range settings (negative noise, dropout > 1, ...).
void validate(const SensorConfig& config);

// Unit ray directions of frame `frame` in the sensor frame. The rosette
// continues from one frame to the next, so it never repeats exactly.
std::vector<Vec3> rayDirections(const SensorConfig& config, std::size_t frame);

// When ray `ray` of a frame fires, as a share of the sweep in [0, 1): a
// spinning sensor fires all channels of a column at once, column after
// column; a rosette fires ray after ray.
double firingShare(const SensorConfig& config, std::size_t ray);

// One return, with what the tests need to check it.
struct Return {
  Vec3 point = Vec3::Zero();  // sensor frame, measured (noisy) range
  double time = 0.0;          // s since the sweep's start (raw sweeps; else 0)
  double true_range = 0.0;
  float intensity = 0.0f;
  std::uint32_t primitive = 0;  // World primitive that was hit
};

// Scans frame `frame` from `sensor_pose` (sensor to world). Deterministic in
// (seed, frame): the noise comes from a generator of that frame alone.
std::vector<Return> scanReturns(const World& world, const Pose& sensor_pose, const SensorConfig& config,
                                std::uint64_t seed, std::size_t frame);
// The sensor's pose (sensor to world) a time (s) after the sweep's start.
using SweepMotion = std::function<Pose(double)>;
// A raw sweep lasting `period` s: each ray cast from motion(its time).
std::vector<Return> sweepReturns(const World& world, const SweepMotion& motion, double period,
                                 const SensorConfig& config, std::uint64_t seed, std::size_t frame);

// The same scan as a float cloud with intensity.
PointCloud scan(const World& world, const Pose& sensor_pose, const SensorConfig& config, std::uint64_t seed,
                std::size_t frame);

}  // namespace hba::sim

namespace hba {
template <>
struct EnumNames<sim::SensorModel> {
  static constexpr const char* what = "sensor";
  static constexpr EnumName<sim::SensorModel> names[] = {{sim::SensorModel::Vlp16, "vlp16"},
                                                         {sim::SensorModel::Hdl32, "hdl32"},
                                                         {sim::SensorModel::Hdl64, "hdl64"},
                                                         {sim::SensorModel::Os128, "os128"},
                                                         {sim::SensorModel::Livox, "livox"}};
};
}  // namespace hba
