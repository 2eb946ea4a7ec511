#pragma once
// A small scan folder (binary PCDs, KITTI poses, times.txt) and the ROS 1
// bag Debian's python3-rosbag writes from it (tests/rec/write_ros1_bag.py).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/pcd.hpp"
#include "hba/rec/recording.hpp"
#include "test_support.hpp"

namespace hba::test {

struct ScanFolder {
  std::vector<PointCloud> scans;
  std::vector<Pose> poses;
  std::vector<double> stamps;
};

// `n` scans of random points (integer intensities), poses turning along a
// curve, stamps 0.1 s apart in Unix time.
inline ScanFolder writeScanFolder(const std::filesystem::path& dir, std::size_t n) {
  std::filesystem::create_directories(dir / "Scans");
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-30.0f, 30.0f);
  std::uniform_int_distribution<int> intensity(0, 255);
  ScanFolder folder;
  std::ofstream poses(dir / "odom_poses.txt"), times(dir / "times.txt");
  poses.precision(17);
  times.precision(17);
  for (std::size_t k = 0; k < n; ++k) {
    PointCloud scan;
    for (int p = 0; p < 200 + static_cast<int>(k); ++p) {
      scan.add(Vec3f(coordinate(rng), coordinate(rng), coordinate(rng)), static_cast<float>(intensity(rng)));
    }
    char name[32];
    std::snprintf(name, sizeof(name), "%06zu.pcd", k);
    io::writePcd(dir / "Scans" / name, scan);
    const double a = 0.07 * static_cast<double>(k);
    const Quat q = Quat(Eigen::AngleAxisd(a, Vec3::UnitZ()) * Eigen::AngleAxisd(0.3 * a, Vec3::UnitX()));
    const Pose pose(q, Vec3(2.0 * std::sin(a), 3.0 * a, 0.1 * a));
    const Mat3 R = pose.R();
    for (int r = 0; r < 3; ++r) {
      poses << R(r, 0) << ' ' << R(r, 1) << ' ' << R(r, 2) << ' ' << pose.t[r] << (r < 2 ? ' ' : '\n');
    }
    const double stamp = 1600000000.0 + 0.1 * static_cast<double>(k);
    times << stamp << '\n';
    folder.scans.push_back(scan);
    folder.poses.push_back(pose);
    folder.stamps.push_back(stamp);
  }
  return folder;
}

// Runs the writer; 77 means python3-rosbag is missing. Debian's python
// first: python3-rosbag installs there, whatever python3 a PATH finds.
inline int writeBag(const std::filesystem::path& folder, const std::filesystem::path& bag,
                    const std::string& flags = "") {
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const CommandResult result = runCommand(python + " " + std::string(HBA_ROS1_BAG_WRITER) + " " +
                                          folder.string() + " " + bag.string() + " " + flags);
  if (result.exit_code != 0 && result.exit_code != 77) ADD_FAILURE() << result.output;
  return result.exit_code;
}

// Runs the MCAP writer (npm's @mcap/core + @foxglove/rosmsg2-serialization);
// 77 means node, npm or the registry is missing. `layout`: see write_mcap.mjs.
inline int writeMcap(const std::filesystem::path& folder, const std::filesystem::path& mcap,
                     const std::string& compression = "zstd", std::size_t scans = 0,
                     const std::string& layout = "indexed") {
  const CommandResult result =
      runCommand("bash " + std::string(HBA_MCAP_WRITER) + " " + folder.string() + " " + mcap.string() + " " +
                 compression + " " + std::to_string(scans) + " " + layout);
  if (result.exit_code != 0 && result.exit_code != 77) ADD_FAILURE() << result.output;
  return result.exit_code;
}

// A rosbag2 folder of sqlite3 files (`split` of them): the CDR messages of
// the MCAP writer's serializer stored by write_db3.py with Python's sqlite3.
// `flags`: more of write_db3.py's (--wal).
inline int writeDb3(const std::filesystem::path& folder, const std::filesystem::path& out, int split = 1,
                    const std::string& flags = "") {
  const std::filesystem::path lines = out.string() + ".jsonl";
  const int written = writeMcap(folder, lines, "cdr");
  if (written != 0) return written;
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const CommandResult result =
      runCommand(python + " " + std::string(HBA_DB3_WRITER) + " " + lines.string() + " " + out.string() +
                 " --split " + std::to_string(split) + " " + flags);
  if (result.exit_code != 0) ADD_FAILURE() << result.output;
  return result.exit_code;
}

// An MCAP file's bytes with its chunks' compression `from` named `to`, in
// its data section only (up to the summary the footer places, or the end).
inline std::string renamedChunkCompression(std::string bytes, const std::string& from,
                                           const std::string& to) {
  std::uint64_t summary_start = 0;
  if (bytes.size() >= 37) std::memcpy(&summary_start, bytes.data() + bytes.size() - 37 + 9, 8);
  const std::size_t end = summary_start > 0 && summary_start < bytes.size() ? summary_start : bytes.size();
  for (std::size_t at = bytes.find(from); at != std::string::npos && at < end;
       at = bytes.find(from, at + 1)) {
    bytes.replace(at, from.size(), to);
  }
  return bytes;
}

inline double angleBetween(const Pose& a, const Pose& b) {
  return Eigen::AngleAxisd(a.q.inverse() * b.q).angle();
}

// The message of the hba::Error that opening `path` and reading every scan
// throws ("" if none).
inline std::string openError(const std::filesystem::path& path, const rec::RecordingOptions& options = {}) {
  try {
    const rec::Recording recording = rec::Recording::open(path, options);
    for (std::size_t i = 0; i < recording.size(); ++i) recording.loadScan(i);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace hba::test

// Runs a writer (an int-returning call); skips the test where it says 77.
#define WRITTEN_OR_SKIP(call, missing)            \
  do {                                            \
    const int written = (call);                   \
    if (written == 77) GTEST_SKIP() << (missing); \
    ASSERT_EQ(written, 0);                        \
  } while (false)
#define WRITE_BAG_OR_SKIP(folder, bag, flags) \
  WRITTEN_OR_SKIP(::hba::test::writeBag(folder, bag, flags), "python3-rosbag is not installed")
#define WRITE_MCAP_OR_SKIP(folder, mcap, compression)                \
  WRITTEN_OR_SKIP(::hba::test::writeMcap(folder, mcap, compression), \
                  "node, npm or the npm registry is missing")
#define WRITE_DB3_OR_SKIP(folder, out, split) \
  WRITTEN_OR_SKIP(::hba::test::writeDb3(folder, out, split), "node, npm or the npm registry is missing")
