// Scans named by time paired with a stamped trajectory: each scan takes the
// pose nearest in time. Odometry often starts a little after the recording
// (initialization) or ends before it; those scans are left out and said so.
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "dataset_parts.hpp"
#include "hba/core/error.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

double medianInterval(const std::vector<double>& stamps) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < stamps.size(); ++i) steps.push_back(stamps[i] - stamps[i - 1]);
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

// Index of the stamp nearest to `t` in the ascending `stamps`.
std::size_t nearest(const std::vector<double>& stamps, double t) {
  const auto after = std::lower_bound(stamps.begin(), stamps.end(), t);
  if (after == stamps.begin()) return 0;
  if (after == stamps.end()) return stamps.size() - 1;
  const auto before = after - 1;
  return static_cast<std::size_t>((t - *before <= *after - t ? before : after) - stamps.begin());
}

std::string describeLeftOut(const std::vector<std::size_t>& left_out) {
  std::string text;
  for (std::size_t k = 0; k < std::min<std::size_t>(left_out.size(), 5); ++k) {
    text += (k ? ", " : "") + std::to_string(left_out[k]);
  }
  return left_out.size() > 5 ? text + ", ..." : text;
}

}  // namespace

TimeMatch matchByTime(const std::vector<double>& scan_stamps, const std::vector<double>& pose_stamps,
                      const fs::path& scans_dir, const fs::path& poses_file, Notes& notes) {
  if (!std::is_sorted(pose_stamps.begin(), pose_stamps.end())) {
    failAt(poses_file, "the timestamps are not in increasing order; cannot pair scans by time");
  }
  const double interval = medianInterval(scan_stamps);
  const double tolerance = interval > 0.0 ? 0.5 * interval : 0.05;
  TimeMatch match;
  std::vector<std::size_t> left_out;
  std::vector<double> offsets;
  for (std::size_t i = 0; i < scan_stamps.size(); ++i) {
    const std::size_t pose = nearest(pose_stamps, scan_stamps[i]);
    const double offset = pose_stamps[pose] - scan_stamps[i];
    if (!(std::abs(offset) <= tolerance)) {
      left_out.push_back(i);
      continue;
    }
    if (!match.pose_of_scan.empty() && match.pose_of_scan.back() == pose) {
      // Two scans nearest to one pose (a pose stamped between them): the
      // closer one keeps it, the other is left out.
      if (std::abs(offset) >= offsets.back()) {
        left_out.push_back(i);
        continue;
      }
      left_out.push_back(match.kept_scans.back());
      match.pose_of_scan.pop_back();
      match.kept_scans.pop_back();
      offsets.pop_back();
    }
    match.pose_of_scan.push_back(pose);
    match.kept_scans.push_back(i);
    offsets.push_back(std::abs(offset));
  }
  if (match.kept_scans.empty() || match.kept_scans.size() * 2 < scan_stamps.size()) {
    failAt(scans_dir,
           fmt::format("only {} of {} scans (named by time, {:.3f} to {:.3f} s) have a pose "
                       "within {:.3f} s in {} ({:.3f} to {:.3f} s); are both in seconds of the "
                       "same clock?",
                       match.kept_scans.size(), scan_stamps.size(), scan_stamps.front(), scan_stamps.back(),
                       tolerance, poses_file.string(), pose_stamps.front(), pose_stamps.back()));
  }
  std::sort(left_out.begin(), left_out.end());
  std::sort(offsets.begin(), offsets.end());
  notes.push_back({DatasetNote::Level::Info,
                   fmt::format("scans paired with the poses of {} by time (median difference {:.4f} s, "
                               "largest {:.4f} s)",
                               poses_file.string(), offsets[offsets.size() / 2], offsets.back())});
  if (!left_out.empty()) {
    notes.push_back({DatasetNote::Level::Warning,
                     fmt::format("{} of {} scans have no pose within {:.3f} s and are left out (scans {})",
                                 left_out.size(), scan_stamps.size(), tolerance, describeLeftOut(left_out))});
  }
  if (match.pose_of_scan.size() < pose_stamps.size()) {
    notes.push_back({DatasetNote::Level::Info, fmt::format("{} poses have no scan and are not used",
                                                           pose_stamps.size() - match.pose_of_scan.size())});
  }
  return match;
}

}  // namespace hba::io::detail
