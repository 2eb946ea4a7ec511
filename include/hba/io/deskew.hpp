#pragma once
// Raw sweeps. A spinning or solid-state LiDAR measures a sweep's points one
// by one while it moves, so each point sits in the sensor frame of its own
// instant. Deskewing moves every point into the frame of the sweep's stamp
// by the motion the trajectory gives between the two instants.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::io {

// auto: deskew when the scans carry point times and the trajectory is dense
// enough to follow the motion within a sweep; on: always (refused when it
// cannot); off: never.
enum class DeskewMode { Auto, On, Off };

// How a sweep's recorded point times read as seconds.
struct PointTimeReading {
  double scale = 1.0;         // seconds per recorded unit
  bool absolute = false;      // on the stamps' clock; else counted from the stamp
  double clock_offset = 0.0;  // s added to absolute times (a recording's --time-offset)

  double secondsSinceStamp(double raw, double stamp) const {
    return absolute ? raw * scale + clock_offset - stamp : raw * scale;
  }
  // "ns since the scan's stamp", "absolute s", ...
  std::string describe() const;
};

// The unit and origin of one sweep's point times, judged from their values:
// absolute when they lie within a minute of the stamp (on a clock of real
// dates, stamp > 1e5 s) in s, ms, µs or ns; otherwise counted from the stamp
// in the largest of those units that keeps the sweep within 2 s. Nullopt
// when the times do not spread (all equal) or fit no unit.
std::optional<PointTimeReading> readPointTimes(const std::vector<double>& raw, double stamp);

// The sensor's pose (sensor to world) at time t, on the stamps' clock.
using PoseAtTime = std::function<Pose(double)>;

// Moves every point of `cloud` to where the sensor saw it from at `stamp`
// and drops the times. Motion is sampled every 20 µs of the sweep at most
// (a point moves < 1 mm at 30 m/s). Throws hba::Error naming `what` when a
// point's time lies more than 1 s from the stamp (times misread).
void deskew(PointCloud& cloud, const PointTimeReading& reading, double stamp, const PoseAtTime& pose_at,
            const std::string& what);

}  // namespace hba::io

namespace hba {
template <>
struct EnumNames<io::DeskewMode> {
  static constexpr const char* what = "deskew mode";
  static constexpr EnumName<io::DeskewMode> names[] = {
      {io::DeskewMode::Auto, "auto"}, {io::DeskewMode::On, "on"}, {io::DeskewMode::Off, "off"}};
};
}  // namespace hba
