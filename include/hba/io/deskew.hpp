#pragma once
// Raw sweeps. A spinning or solid-state LiDAR measures a sweep's points one
// by one while it moves, so each point sits in the sensor frame of its own
// instant. Deskewing moves every point into the frame of the sweep's stamp
// by the motion the trajectory gives between the two instants.
#include <cstddef>
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

// The unit and origin of one sweep's point times, judged from the bulk of
// their values (all but the lowest and highest 1 %, so a driver's stray
// values do not decide): absolute when their median lies within a minute of
// the stamp (on a clock of real dates, stamp > 1e5 s) in s, ms, µs or ns;
// otherwise counted from the stamp in the largest of those units that keeps
// the bulk within 2 s. Nullopt when the bulk does not spread (all equal) or
// fits no unit.
std::optional<PointTimeReading> readPointTimes(const std::vector<double>& raw, double stamp);

// A point whose time lies further than this (s) from its scan's stamp was
// not measured in that sweep, or its time is misread: it cannot be deskewed.
inline constexpr double kFarthestTime = 1.0;
// The share of a sweep's points such stray times may have: they are left
// out. More, and the times as a whole are misread: the scan is refused.
inline constexpr double kMostStrayTimes = 0.01;

// Points deskew() left out, their time too far from the stamp.
struct StrayTimes {
  std::size_t count = 0;
  double farthest = 0.0;  // s from the stamp, signed (NaN for a time that is not a number)
};

// The sensor's pose (sensor to world) at time t, on the stamps' clock.
using PoseAtTime = std::function<Pose(double)>;

// Moves every point of `cloud` to where the sensor saw it from at `stamp`
// and drops the times. Motion is sampled every 20 µs of the sweep at most
// (a point moves < 1 mm at 30 m/s). Points whose time lies more than
// kFarthestTime from the stamp are left out and counted, up to
// kMostStrayTimes of the sweep; beyond that throws hba::Error naming `what`
// (times misread).
StrayTimes deskew(PointCloud& cloud, const PointTimeReading& reading, double stamp, const PoseAtTime& pose_at,
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
