// Dataset: whether and how raw sweeps are deskewed as they load.
#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <utility>

#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_file.hpp"

namespace hba::io {
namespace {

// Poses further apart than this (s) cannot follow the motion within a sweep
// (0.1 s) well enough for --deskew auto: 4 Hz and denser odometry can.
constexpr double kSparsestMotion = 0.25;
// Scans whose point times decide their unit: the first, the last and evenly
// between, so that neither a first partial sweep nor one odd scan decides.
constexpr std::size_t kSampledScans = 7;

std::vector<std::size_t> sampledScans(std::size_t count) {
  std::vector<std::size_t> picks;
  const std::size_t n = std::min(count, kSampledScans);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = n == 1 ? 0 : k * (count - 1) / (n - 1);
    if (picks.empty() || picks.back() != i) picks.push_back(i);
  }
  return picks;
}

// "scans 0, 12 and 24"
std::string scanList(const std::vector<std::size_t>& scans) {
  std::string text = scans.size() == 1 ? "scan " : "scans ";
  for (std::size_t k = 0; k < scans.size(); ++k) {
    text += (k == 0 ? "" : k + 1 == scans.size() ? " and " : ", ") + std::to_string(scans[k]);
  }
  return text;
}

// The sampled scans that read their point times one way.
struct TimeReadingVote {
  PointTimeReading reading;
  std::vector<std::size_t> scans;
};

bool sameReading(const PointTimeReading& a, const PointTimeReading& b) {
  return a.scale == b.scale && a.absolute == b.absolute;
}

// What the sampled scans say of their point times: the readings, most
// scans' first; the scans without times, and those whose times fit no unit.
struct TimeVotes {
  std::vector<TimeReadingVote> votes;
  std::vector<std::size_t> untimed, unread;
};

// `scans` are (index, scan) pairs, absent where a scan could not be read.
TimeVotes countTimeVotes(const std::vector<std::pair<std::size_t, std::optional<PointCloud>>>& scans,
                         const std::vector<double>& stamps, double clock_offset) {
  TimeVotes result;
  for (const auto& [i, read] : scans) {
    if (!read) continue;
    if (!read->hasTime()) {
      result.untimed.push_back(i);
      continue;
    }
    const std::optional<PointTimeReading> reading = readPointTimes(read->time, stamps[i] - clock_offset);
    if (!reading) {
      result.unread.push_back(i);
      continue;
    }
    const auto same = std::find_if(result.votes.begin(), result.votes.end(), [&](const TimeReadingVote& v) {
      return sameReading(v.reading, *reading);
    });
    if (same == result.votes.end()) {
      result.votes.push_back({*reading, {i}});
    } else {
      same->scans.push_back(i);
    }
  }
  std::stable_sort(
      result.votes.begin(), result.votes.end(),
      [](const TimeReadingVote& a, const TimeReadingVote& b) { return a.scans.size() > b.scans.size(); });
  return result;
}

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
  // Scan i as stored, or nothing when it cannot be read (under auto: it is
  // reported when it is loaded).
  const auto loadRaw = [&](std::size_t i) -> std::optional<PointCloud> {
    try {
      return recording_ ? recording_->loadScan(i) : readScan(scan_paths_.at(i));
    } catch (const Error&) {
      if (asked) throw;
      return std::nullopt;
    }
  };
  const std::vector<std::size_t> sampled = sampledScans(size());
  // Whether the scans carry times at all: the first sampled scan that reads.
  std::size_t next = 0;
  std::optional<PointCloud> first;
  while (!first && next < sampled.size()) first = loadRaw(sampled[next++]);
  if (!first) return;
  if (!first->hasTime()) {
    if (asked) {
      failAt(scanPath(sampled[next - 1]),
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
  // The unit the sampled scans agree on; the scans without times or whose
  // times do not spread tell nothing.
  std::vector<std::pair<std::size_t, std::optional<PointCloud>>> scans;
  for (std::size_t k = next - 1; k < sampled.size(); ++k)
    scans.emplace_back(sampled[k], k + 1 == next ? std::move(first) : loadRaw(sampled[k]));
  const TimeVotes counted = countTimeVotes(scans, trajectory_.stamps, clock_offset);
  const std::vector<TimeReadingVote>& votes = counted.votes;
  const std::vector<std::size_t>& untimed = counted.untimed;
  if (votes.empty()) {
    return cannot("the point times of " + scanList(counted.unread) +
                  " are all equal or fit no unit (s, ms, us, ns)");
  }
  if (votes.size() > 1 && votes[1].scans.size() == votes[0].scans.size()) {
    return cannot(
        fmt::format("the point times of {} read as {}, those of {} as {}: no unit most scans agree on",
                    scanList(votes[0].scans), votes[0].reading.describe(), scanList(votes[1].scans),
                    votes[1].reading.describe()));
  }
  PointTimeReading reading = votes[0].reading;
  reading.clock_offset = clock_offset;
  point_times_ = reading;
  notes_.push_back({DatasetNote::Level::Info,
                    fmt::format("raw sweeps: each deskewed to its stamp by the motion of {} (poses {:.3f} s "
                                "apart); point times read as {} (as in {} of {} scans sampled)",
                                recording_ ? recording_->poseTopic() : std::string("the scans' poses"), gap,
                                reading.describe(), votes[0].scans.size(), sampled.size())});
  for (std::size_t k = 1; k < votes.size(); ++k) {
    notes_.push_back(
        {DatasetNote::Level::Warning,
         fmt::format("the point times of {} would read as {} on their own; read as {}, as most "
                     "scans' are (a partial sweep, or times in another unit)",
                     scanList(votes[k].scans), votes[k].reading.describe(), reading.describe())});
  }
  if (!untimed.empty()) {
    notes_.push_back({DatasetNote::Level::Warning,
                      scanList(untimed) + " carry no point time: such scans are left as recorded"});
  }
}

}  // namespace hba::io
