// Ray directions of spinning and rosette sensors.
#include <cmath>

#include "hba/sim/sensor.hpp"

namespace hba::sim {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kFrameRateHz = 10.0;
// Rotation speeds (rev/s) of the two Risley prisms that draw the rosette;
// the ratio is irrational, so the pattern never closes on itself.
constexpr double kPrismSpeed1 = 121.57;
constexpr double kPrismSpeed2 = -77.73 * 1.0000137;

std::vector<Vec3> spinningDirections(const SensorConfig& c) {
  std::vector<Vec3> directions;
  directions.reserve(c.raysPerFrame());
  // Firing order of a real spinning sensor: all channels of one azimuth, then the next.
  for (int column = 0; column < c.columns; ++column) {
    const double azimuth = 2.0 * M_PI * column / c.columns;
    for (int channel = 0; channel < c.channels; ++channel) {
      const double f = c.channels > 1 ? static_cast<double>(channel) / (c.channels - 1) : 0.5;
      const double elevation =
          (c.min_elevation_deg + f * (c.max_elevation_deg - c.min_elevation_deg)) * kDegToRad;
      directions.emplace_back(std::cos(elevation) * std::cos(azimuth),
                              std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
    }
  }
  return directions;
}

// Two prisms turning at different speeds each deflect the beam by a quarter
// of the field of view; their sum sweeps a rosette over the whole cone.
std::vector<Vec3> rosetteDirections(const SensorConfig& c, std::size_t frame) {
  std::vector<Vec3> directions;
  directions.reserve(c.raysPerFrame());
  const double quarter = 0.25 * c.field_of_view_deg * kDegToRad;
  const double dt = 1.0 / (kFrameRateHz * c.points_per_frame);
  const auto first = static_cast<double>(frame) * c.points_per_frame;
  for (int i = 0; i < c.points_per_frame; ++i) {
    const double t = (first + i) * dt;
    const double a1 = 2.0 * M_PI * std::fmod(kPrismSpeed1 * t, 1.0);
    const double a2 = 2.0 * M_PI * std::fmod(kPrismSpeed2 * t, 1.0);
    const Eigen::Vector2d offset =
        quarter * Eigen::Vector2d(std::cos(a1) + std::cos(a2), std::sin(a1) + std::sin(a2));
    const double off_axis = offset.norm();  // angle from the x axis
    const double around = std::atan2(offset.y(), offset.x());
    directions.emplace_back(std::cos(off_axis), std::sin(off_axis) * std::cos(around),
                            std::sin(off_axis) * std::sin(around));
  }
  return directions;
}

}  // namespace

std::vector<Vec3> rayDirections(const SensorConfig& config, std::size_t frame) {
  return config.model == SensorModel::Livox ? rosetteDirections(config, frame) : spinningDirections(config);
}

}  // namespace hba::sim
