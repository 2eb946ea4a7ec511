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
// The bulk of a sweep's times, whose spread decides the unit: all but the
// lowest and highest 1 %, so that a driver's stray values do not.
constexpr double kBulkTail = 0.01;

// The value at fraction q of the sorted values (0 = least, 1 = greatest),
// the nearest rank: of two values, q = 0.01 is the lower, 0.99 the higher.
double quantile(std::vector<double>& values, double q) {
  const auto at = static_cast<std::ptrdiff_t>(std::lround(q * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + at, values.end());
  return values[static_cast<std::size_t>(at)];
}

const char* unitName(double scale) {
  for (const Unit& unit : kUnits) {
    if (unit.scale == scale) return unit.name;
  }
  return "?";
}

// Drops the points whose time lies beyond kFarthestTime (with their
// intensity and time), keeping `seconds` aligned with the points.
void leaveOutStrays(PointCloud& cloud, std::vector<double>& seconds) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!(std::abs(seconds[i]) <= kFarthestTime)) continue;
    cloud.points[kept] = cloud.points[i];
    if (cloud.hasIntensity()) cloud.intensity[kept] = cloud.intensity[i];
    cloud.time[kept] = cloud.time[i];
    seconds[kept] = seconds[i];
    ++kept;
  }
  cloud.points.resize(kept);
  if (cloud.hasIntensity()) cloud.intensity.resize(kept);
  cloud.time.resize(kept);
  seconds.resize(kept);
}

}  // namespace

std::string PointTimeReading::describe() const {
  return absolute ? fmt::format("absolute {}", unitName(scale))
                  : fmt::format("{} since the scan's stamp", unitName(scale));
}

std::optional<PointTimeReading> readPointTimes(const std::vector<double>& raw, double stamp) {
  std::vector<double> finite;
  finite.reserve(raw.size());
  for (const double t : raw) {
    if (std::isfinite(t)) finite.push_back(t);
  }
  if (finite.empty()) return std::nullopt;
  const double low = quantile(finite, kBulkTail);
  const double high = quantile(finite, 1.0 - kBulkTail);
  if (!(high > low)) return std::nullopt;
  const double middle = quantile(finite, 0.5);
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

StrayTimes deskew(PointCloud& cloud, const PointTimeReading& reading, double stamp, const PoseAtTime& pose_at,
                  const std::string& what) {
  if (cloud.time.size() != cloud.size()) {
    throw Error(fmt::format("{}: {} point times for {} points", what, cloud.time.size(), cloud.size()));
  }
  StrayTimes stray;
  if (cloud.empty()) return stray;
  std::vector<double> seconds(cloud.size());
  double low = INFINITY, high = -INFINITY;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    seconds[i] = reading.secondsSinceStamp(cloud.time[i], stamp);
    if (!(std::abs(seconds[i]) <= kFarthestTime)) {
      ++stray.count;
      if (!(std::abs(seconds[i]) <= std::abs(stray.farthest))) stray.farthest = seconds[i];
      continue;
    }
    low = std::min(low, seconds[i]);
    high = std::max(high, seconds[i]);
  }
  if (stray.count > 0) {
    if (static_cast<double>(stray.count) > kMostStrayTimes * static_cast<double>(cloud.size())) {
      throw Error(fmt::format(
          "{}: {} of {} points have times more than {:g} s from the scan's stamp (the farthest lies {:.3g} s "
          "from the scan's stamp, read as {}): more than {:g} % of the sweep, so the times are not the "
          "sweep's or are misread (give --deskew off to leave the scans as recorded)",
          what, stray.count, cloud.size(), kFarthestTime, stray.farthest, reading.describe(),
          100.0 * kMostStrayTimes));
    }
    leaveOutStrays(cloud, seconds);
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
  return stray;
}

}  // namespace hba::io
