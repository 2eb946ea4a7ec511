#include "hba/io/deskew.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"

namespace hba::io {
namespace {

struct Unit {
  double scale;
  const char* name;
};
constexpr Unit kUnits[] = {{1.0, "s"}, {1e-3, "ms"}, {1e-6, "us"}, {1e-9, "ns"}};

constexpr double kRealClock = 1e5;     // s: stamps beyond this are dates, not times since a start
constexpr double kLongestSweep = 2.0;  // s: no LiDAR sweeps longer
constexpr double kStep = 2e-5;         // s between motion samples
constexpr std::size_t kMostSamples = 100000;

const char* unitName(double scale) {
  for (const Unit& unit : kUnits) {
    if (unit.scale == scale) return unit.name;
  }
  return "?";
}

}  // namespace

std::string PointTimeReading::describe() const {
  return absolute ? fmt::format("absolute {}", unitName(scale))
                  : fmt::format("{} since the scan's stamp", unitName(scale));
}

std::optional<PointTimeReading> readPointTimes(const std::vector<double>& raw, double stamp) {
  double low = INFINITY, high = -INFINITY;
  for (const double t : raw) {
    if (!std::isfinite(t)) continue;
    low = std::min(low, t);
    high = std::max(high, t);
  }
  if (!(high > low)) return std::nullopt;
  const double middle = 0.5 * (low + high);
  if (std::abs(stamp) > kRealClock) {
    for (const Unit& unit : kUnits) {
      if (std::abs(middle * unit.scale - stamp) < 60.0) return PointTimeReading{unit.scale, true, 0.0};
    }
  }
  const double largest = std::max(std::abs(low), std::abs(high));
  for (const Unit& unit : kUnits) {
    if (largest * unit.scale <= kLongestSweep) return PointTimeReading{unit.scale, false, 0.0};
  }
  return std::nullopt;
}

void deskew(PointCloud& cloud, const PointTimeReading& reading, double stamp, const PoseAtTime& pose_at,
            const std::string& what) {
  if (cloud.time.size() != cloud.size()) {
    throw Error(fmt::format("{}: {} point times for {} points", what, cloud.time.size(), cloud.size()));
  }
  if (cloud.empty()) return;
  std::vector<double> seconds(cloud.size());
  double low = INFINITY, high = -INFINITY;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    seconds[i] = reading.secondsSinceStamp(cloud.time[i], stamp);
    if (!(std::abs(seconds[i]) <= 1.0)) {
      throw Error(
          fmt::format("{}: a point's time lies {:.3g} s from the scan's stamp (read as {}): the "
                      "times are not the sweep's (give --deskew off to leave the scans as recorded)",
                      what, seconds[i], reading.describe()));
    }
    low = std::min(low, seconds[i]);
    high = std::max(high, seconds[i]);
  }
  // The sensor's motion from the stamp, sampled evenly over the sweep.
  const std::size_t samples =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil((high - low) / kStep)) + 1, 2, kMostSamples);
  const double step = (high - low) / static_cast<double>(samples - 1);
  const Pose at_stamp = pose_at(stamp).inverse();
  std::vector<Eigen::Matrix3f> rotations(samples);
  std::vector<Vec3f> translations(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    const Pose motion = at_stamp * pose_at(stamp + low + step * static_cast<double>(k));
    rotations[k] = motion.R().cast<float>();
    translations[k] = motion.t.cast<float>();
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double position = step > 0.0 ? (seconds[i] - low) / step : 0.0;
    const auto k = std::min(samples - 1, static_cast<std::size_t>(std::lround(position)));
    cloud.points[i] = rotations[k] * cloud.points[i] + translations[k];
  }
  cloud.time.clear();
  cloud.time.shrink_to_fit();
}

}  // namespace hba::io
