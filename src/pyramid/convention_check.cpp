#include "hba/pyramid/convention_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "hba/voxel/voxel_key.hpp"

namespace hba::pyramid {
namespace {

using KeySet = std::unordered_set<voxel::VoxelKey, voxel::VoxelKeyHash>;

double rotationDeg(const Pose& a, const Pose& b) {
  return a.q.angularDistance(b.q) * 180.0 / M_PI;
}

// Stretches of consecutive frames, spread over the sequence, each long
// enough (in path or turn) that wrong poses would smear the map visibly.
std::vector<std::vector<std::size_t>> pickStretches(const std::vector<Pose>& poses,
                                                    const ConventionSettings& s) {
  std::vector<std::vector<std::size_t>> stretches;
  const std::size_t n = poses.size();
  for (std::size_t k = 0; k < s.max_stretches; ++k) {
    const std::size_t first = n * k / s.max_stretches;
    double path = 0.0;
    std::size_t last = first;
    while (last + 1 < n && path < s.stretch_length &&
           rotationDeg(poses[first], poses[last]) < s.stretch_rotation_deg) {
      path += (poses[last + 1].t - poses[last].t).norm();
      ++last;
    }
    const bool moved = path >= s.stretch_length || rotationDeg(poses[first], poses[last]) >= s.stretch_rotation_deg;
    if (!moved || last == first) continue;
    std::vector<std::size_t> frames;
    const std::size_t count = std::min(s.stretch_scans, last - first + 1);
    for (std::size_t j = 0; j < count; ++j) frames.push_back(first + (last - first) * j / (count - 1));
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    if (stretches.empty() || stretches.back().front() != frames.front()) stretches.push_back(frames);
  }
  return stretches;
}

// A camera's axes (x right, y down, z forward) in a z-up, x-forward sensor's.
Pose cameraAxes() {
  Mat3 sensor_to_camera;
  sensor_to_camera << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  return Pose(sensor_to_camera, Vec3::Zero());
}

void addVoxels(const PointCloud& scan, const Pose& pose, double voxel, KeySet& keys) {
  const Mat3 R = pose.R();
  for (const Vec3f& p : scan.points) keys.insert(voxel::VoxelKey::of(R * p.cast<double>() + pose.t, voxel));
}

}  // namespace

ConventionCheck checkConventions(const ScanSource& scans, const std::vector<Pose>& poses,
                                 const ConventionSettings& s) {
  ConventionCheck check;
  const std::vector<std::vector<std::size_t>> stretches = pickStretches(poses, s);
  check.stretches = stretches.size();
  if (stretches.empty()) return check;
  const Pose to_camera = cameraAxes(), from_camera = to_camera.inverse();
  double given = 0.0, inverted = 0.0, world = 0.0, camera = 0.0, single = 0.0;
  for (const std::vector<std::size_t>& frames : stretches) {
    KeySet as_given, as_inverted, as_world, as_camera;
    for (std::size_t i : frames) {
      const PointCloud scan = scans.load(i);
      KeySet own;
      addVoxels(scan, Pose::identity(), s.voxel, own);
      single += static_cast<double>(own.size()) / static_cast<double>(frames.size());
      addVoxels(scan, poses[i], s.voxel, as_given);
      addVoxels(scan, poses[i].inverse(), s.voxel, as_inverted);
      addVoxels(scan, from_camera * poses[i] * to_camera, s.voxel, as_camera);
      as_world.insert(own.begin(), own.end());
    }
    given += static_cast<double>(as_given.size());
    inverted += static_cast<double>(as_inverted.size());
    world += static_cast<double>(as_world.size());
    camera += static_cast<double>(as_camera.size());
  }
  if (single <= 0.0) return check;
  check.as_given = given / single;
  check.inverted = inverted / single;
  check.in_world = world / single;
  check.camera = camera / single;
  const double best_other = std::min({check.inverted, check.in_world, check.camera});
  if (best_other > s.decisive_ratio * check.as_given) return check;
  const std::string scores = fmt::format(
      "merged over {} stretches of the path, the map occupies {:.2f} scans' worth of {} m voxels with the "
      "poses as given, {:.2f} with each pose inverted, {:.2f} with no poses at all, {:.2f} with the poses "
      "read as a camera's",
      check.stretches, check.as_given, s.voxel, check.inverted, check.in_world, check.camera);
  if (check.camera == best_other) {
    check.verdict = ConventionVerdict::CameraPoses;
    check.message = "the poses look like a camera's (x right, y down, z forward, as KITTI's camera 0): " +
                    scores + ". hba needs poses of the scans' sensor; give the sensor-to-camera "
                    "transform with --calib calib.txt (KITTI's Tr) or --extrinsic";
  } else if (check.inverted == best_other) {
    check.verdict = ConventionVerdict::PosesInverted;
    check.message = "the poses look inverted (world-to-sensor): " + scores +
                    ". hba expects sensor-to-world poses (p_world = R p + t); run again with --invert-poses";
  } else {
    check.verdict = ConventionVerdict::ScansInWorld;
    check.message = "the scans look already moved into the world frame: " + scores +
                    ". hba expects scans in the sensor frame; run again with --scans-in-world";
  }
  check.message += " (or --no-convention-check to run as given)";
  return check;
}

}  // namespace hba::pyramid
