#include "harness.hpp"
#include "harness_checks.hpp"

#include <cmath>
#include <cstdlib>

#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

namespace {

// The same file read in double: finite points, one intensity each, and
// hba's cloud holds each of them as a float relative to its origin (it drops
// only those whose float overflows).
void checkWideAgainstCloud(const io::WideCloud& wide, const PointCloud& cloud) {
  if (wide.hasIntensity() && wide.intensity.size() != wide.size()) std::abort();
  for (const Vec3& p : wide.points) {
    if (!p.allFinite()) std::abort();
  }
  if (cloud.size() > wide.size()) std::abort();
  if (cloud.size() != wide.size()) return;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.points[i] != (wide.points[i] - cloud.origin).cast<float>()) std::abort();
  }
}

// The pose readers reject non-finite numbers and renormalize quaternions.
void checkTrajectory(const Trajectory& trajectory) {
  if (trajectory.hasStamps() && trajectory.stamps.size() != trajectory.size()) std::abort();
  for (const Pose& pose : trajectory.poses) {
    if (!pose.t.allFinite()) std::abort();
    checkRotation(pose.q);
  }
}

void feedPoses(const fs::path& input, io::PoseFormat format) {
  rejectOnlyWithError([&] { checkTrajectory(io::readPoses(input, format)); });
  // Format detection runs on the same bytes whatever the declared format.
  rejectOnlyWithError([&] { checkTrajectory(io::readPoses(input)); });
}

}  // namespace

void feedPcd(const fs::path& input) {
  rejectOnlyWithError([&] { io::readPcdHeader(input); });
  rejectOnlyWithError([&] { checkCloud(io::readPcd(input)); });
}

void feedPly(const fs::path& input) {
  rejectOnlyWithError([&] { checkCloud(io::readPly(input)); });
}

// As `hba info` (the header alone) and every command (the points) read it.
void feedLas(const fs::path& input) {
  rejectOnlyWithError([&] { io::readLasHeader(input); });
  rejectOnlyWithError([&] {
    const PointCloud cloud = io::readLas(input);
    checkCloud(cloud);
    checkWideAgainstCloud(io::scanFormatOf("fuzzed.las").read_wide(input), cloud);
  });
}

void feedKittiBin(const fs::path& input) {
  rejectOnlyWithError([&] { checkCloud(io::readKittiBin(input)); });
}

void feedHbaPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Hba); }
void feedKittiPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Kitti); }
void feedTumPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Tum); }

}  // namespace hba::fuzz
