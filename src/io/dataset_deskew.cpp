// Dataset: whether and how raw sweeps are deskewed as they load.
#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_file.hpp"

namespace hba::io {
namespace {

// Poses further apart than this (s) cannot follow the motion within a sweep
// (0.1 s) well enough for --deskew auto: 4 Hz and denser odometry can.
constexpr double kSparsestMotion = 0.25;

double medianGap(const std::vector<double>& stamps) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < stamps.size(); ++i) gaps.push_back(stamps[i] - stamps[i - 1]);
  if (gaps.empty()) return INFINITY;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

// "t, time, timestamp or offset_time"
std::string timeFieldNames() {
  std::string names;
  const std::size_t count = std::size(kPointTimeFields);
  for (std::size_t k = 0; k < count; ++k) {
    names += (k == 0 ? "" : k + 1 == count ? " or " : ", ") + std::string(kPointTimeFields[k]);
  }
  return names;
}

}  // namespace

Pose Dataset::sensorPoseAt(double t) const {
  if (deskew_motion_) return poseAtTime(*deskew_motion_, t);
  if (recording_) return frame_left_ * poseAtTime(recording_->recordedTrajectory(), t) * frame_right_;
  return poseAtTime(trajectory_, t);
}

void Dataset::deskewBy(const std::vector<Pose>& sensor_poses) {
  if (sensor_poses.size() != size()) {
    throw Error(fmt::format("deskew: {} poses for {} scans", sensor_poses.size(), size()));
  }
  deskew_motion_ = Trajectory{sensor_poses, trajectory_.stamps};
}

void Dataset::prepareDeskew(DeskewMode mode) {
  point_times_.reset();
  if (mode == DeskewMode::Off || size() == 0) return;
  const bool asked = mode == DeskewMode::On;
  // Under auto a reason not to deskew is a note; asked for, it is an error.
  const auto cannot = [&](const std::string& why) {
    if (asked) failAt(root_, "--deskew on: " + why);
    notes_.push_back({DatasetNote::Level::Warning, "the scans carry point times but are left as recorded: " +
                                                       why + " (--deskew on to insist, off to silence)"});
  };
  PointCloud first;
  try {
    first = recording_ ? recording_->loadScan(0) : readScan(scan_paths_.at(0));
  } catch (const Error&) {
    if (asked) throw;
    return;  // a scan that cannot be read is reported when it is loaded
  }
  if (!first.hasTime()) {
    if (asked) {
      failAt(scanPath(0),
             "--deskew on, but the scan has no per-point time (a field named " + timeFieldNames() + ")");
    }
    return;
  }
  if (scans_in_world_) return cannot("the scans were saved in the world frame, deskewed already");
  if (stamps_source_.empty() || trajectory_.stamps.size() != size()) {
    return cannot("the scans have no stamps (give --times)");
  }
  const Trajectory& motion = recording_ ? recording_->recordedTrajectory() : trajectory_;
  const double gap = medianGap(motion.stamps);
  if (!asked && gap > kSparsestMotion) {
    return cannot(
        fmt::format("the trajectory's poses lie {:.2f} s apart (median), too far to follow the "
                    "motion within a sweep",
                    gap));
  }
  const double clock_offset = recording_ ? recording_->timeOffset() : 0.0;
  std::optional<PointTimeReading> reading = readPointTimes(first.time, trajectory_.stamps[0] - clock_offset);
  if (!reading) return cannot("the first scan's point times are all equal or fit no unit (s, ms, us, ns)");
  reading->clock_offset = clock_offset;
  point_times_ = reading;
  notes_.push_back({DatasetNote::Level::Info,
                    fmt::format("raw sweeps: each deskewed to its stamp by the motion of {} (poses {:.3f} s "
                                "apart); point times read as {}",
                                recording_ ? recording_->poseTopic() : std::string("the scans' poses"), gap,
                                reading->describe())});
}

}  // namespace hba::io
