#include "harness.hpp"

#include <cmath>
#include <cstdlib>

#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::fuzz {
namespace fs = std::filesystem;

namespace {

// The scan readers drop NaN/Inf points and keep intensity one per point.
void checkCloud(const PointCloud& cloud) {
  if (cloud.hasIntensity() && cloud.intensity.size() != cloud.size()) std::abort();
  for (const Vec3f& p : cloud.points) {
    if (!p.allFinite()) std::abort();
  }
}

// The pose readers reject non-finite numbers and renormalize quaternions.
void checkTrajectory(const Trajectory& trajectory) {
  if (trajectory.hasStamps() && trajectory.stamps.size() != trajectory.size()) std::abort();
  for (const Pose& pose : trajectory.poses) {
    if (!pose.t.allFinite() || !pose.q.coeffs().allFinite()) std::abort();
    if (std::abs(pose.q.norm() - 1.0) > 1e-6) std::abort();
  }
}

template <typename Parse>
void rejectOnlyWithError(Parse parse) {
  try {
    parse();
  } catch (const Error&) {
    // The documented outcome for bad input.
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

void feedKittiBin(const fs::path& input) {
  rejectOnlyWithError([&] { checkCloud(io::readKittiBin(input)); });
}

void feedHbaPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Hba); }
void feedKittiPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Kitti); }
void feedTumPoses(const fs::path& input) { feedPoses(input, io::PoseFormat::Tum); }

}  // namespace hba::fuzz
