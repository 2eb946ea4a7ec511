// Writing trajectories, atomically, with the shortest decimal form that reads
// back to the very same double (std::to_chars), so a write/read round trip is
// exact and files stay readable ("0.1", not "0.10000000000000001").
#include <array>
#include <charconv>
#include <ostream>
#include <string>

#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::io {
namespace fs = std::filesystem;

namespace {

// Writes the numbers separated by single spaces, then a newline.
template <std::size_t N>
void writeRow(std::ostream& out, const std::array<double, N>& values) {
  std::array<char, 32> buffer{};
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out << ' ';
    // A double that is +0 after rounding must not print as "-0".
    const double value = values[i] == 0.0 ? 0.0 : values[i];
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    out.write(buffer.data(), result.ptr - buffer.data());
  }
  out << '\n';
}

void writeHbaLine(std::ostream& out, const Pose& pose) {
  writeRow<7>(out, {pose.t.x(), pose.t.y(), pose.t.z(), pose.q.w(), pose.q.x(), pose.q.y(), pose.q.z()});
}

void writeKittiLine(std::ostream& out, const Pose& pose) {
  const Mat3 r = pose.R();
  writeRow<12>(out, {r(0, 0), r(0, 1), r(0, 2), pose.t.x(), r(1, 0), r(1, 1), r(1, 2), pose.t.y(), r(2, 0),
                     r(2, 1), r(2, 2), pose.t.z()});
}

void writeTumLine(std::ostream& out, double stamp, const Pose& pose) {
  writeRow<8>(out,
              {stamp, pose.t.x(), pose.t.y(), pose.t.z(), pose.q.x(), pose.q.y(), pose.q.z(), pose.q.w()});
}

}  // namespace

void writePoses(const fs::path& path, const Trajectory& trajectory, PoseFormat format) {
  if (trajectory.empty()) failAt(path, "refusing to write an empty trajectory (no poses)");
  if (trajectory.hasStamps() && trajectory.stamps.size() != trajectory.size()) {
    failAt(path, "the trajectory has " + std::to_string(trajectory.stamps.size()) + " timestamps for " +
                     std::to_string(trajectory.size()) + " poses");
  }
  writeFileAtomically(path, [&](std::ostream& out) {
    if (format == PoseFormat::Tum) {
      out << (trajectory.hasStamps() ? "# timestamp tx ty tz qx qy qz qw\n"
                                     : "# timestamp tx ty tz qx qy qz qw (no timestamps were "
                                       "given: the time is the scan index)\n");
    }
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
      const Pose& pose = trajectory.poses[i];
      switch (format) {
        case PoseFormat::Hba:
          writeHbaLine(out, pose);
          break;
        case PoseFormat::Kitti:
          writeKittiLine(out, pose);
          break;
        case PoseFormat::Tum:
          writeTumLine(out, trajectory.hasStamps() ? trajectory.stamps[i] : static_cast<double>(i), pose);
          break;
      }
    }
  });
}

void writeTimes(const fs::path& path, const std::vector<double>& stamps) {
  if (stamps.empty()) failAt(path, "refusing to write an empty list of timestamps");
  writeFileAtomically(path, [&](std::ostream& out) {
    for (double stamp : stamps) writeRow<1>(out, {stamp});
  });
}

}  // namespace hba::io
