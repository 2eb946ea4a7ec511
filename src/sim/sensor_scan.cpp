// Casting a frame's rays into the world and turning hits into returns.
#include <algorithm>
#include <cmath>

#include "hba/sim/sensor.hpp"
#include "sim/random.hpp"

namespace hba::sim {
namespace {

// Intensity in [0, 255] like an 8-bit LiDAR: the surface's reflectivity,
// dimmed at grazing incidence (Lambertian) and a little with distance.
float intensityOf(const SurfaceHit& hit, const Vec3& direction, double max_range) {
  const double cos_incidence = std::abs(hit.normal.dot(direction));
  const double falloff = 1.0 - 0.3 * std::min(1.0, hit.distance / max_range);
  const double value = 255.0 * hit.reflectivity * (0.2 + 0.8 * cos_incidence) * falloff;
  return static_cast<float>(std::clamp(std::round(value), 0.0, 255.0));
}

}  // namespace

double firingShare(const SensorConfig& config, std::size_t ray) {
  const std::size_t rays = config.raysPerFrame();
  const std::size_t together =
      config.model == SensorModel::Livox ? 1 : static_cast<std::size_t>(config.channels);
  return static_cast<double>(ray / together * together) / static_cast<double>(rays);
}

std::vector<Return> scanReturns(const World& world, const Pose& sensor_pose, const SensorConfig& config,
                                std::uint64_t seed, std::size_t frame) {
  const auto still = [&sensor_pose](double) { return sensor_pose; };
  return sweepReturns(world, still, 0.0, config, seed, frame);
}

std::vector<Return> sweepReturns(const World& world, const SweepMotion& motion, double period,
                                 const SensorConfig& config, std::uint64_t seed, std::size_t frame) {
  auto rng = makeRng(seed, Stream::Sensor, frame);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Search a little beyond max_range: noise may bring a farther hit inside.
  const double search_range = config.max_range + 5.0 * config.range_noise;

  std::vector<Return> returns;
  const std::vector<Vec3> directions = rayDirections(config, frame);
  returns.reserve(directions.size());
  // Rays that fire together share the sensor's pose.
  double pose_time = -1.0;
  Pose sensor_pose;
  Mat3 rotation = Mat3::Identity();
  for (std::size_t k = 0; k < directions.size(); ++k) {
    const Vec3& direction = directions[k];
    const double time = period * firingShare(config, k);
    if (time != pose_time) {
      pose_time = time;
      sensor_pose = motion(time);
      rotation = sensor_pose.R();
    }
    // Both draws happen for every ray, so a ray's noise never depends on
    // whether an earlier ray hit something.
    const double range_error = config.range_noise * noise(rng);
    const bool dropped = unit(rng) < config.dropout;
    const Ray ray{sensor_pose.t, rotation * direction};
    const auto hit = world.intersect(ray, search_range);
    if (!hit || dropped) continue;
    const double measured = hit->distance + range_error;
    if (measured < config.min_range || measured > config.max_range) continue;
    Return r;
    r.point = direction * measured;
    r.time = time;
    r.true_range = hit->distance;
    r.intensity = intensityOf(*hit, ray.direction, config.max_range);
    r.primitive = hit->primitive;
    returns.push_back(r);
  }
  return returns;
}

PointCloud scan(const World& world, const Pose& sensor_pose, const SensorConfig& config, std::uint64_t seed,
                std::size_t frame) {
  const std::vector<Return> returns = scanReturns(world, sensor_pose, config, seed, frame);
  PointCloud cloud;
  cloud.reserve(returns.size(), true);
  for (const Return& r : returns) cloud.add(r.point.cast<float>(), r.intensity);
  return cloud;
}

}  // namespace hba::sim
