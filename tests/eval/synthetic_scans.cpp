#include "synthetic_scans.hpp"

#include <cstdio>

#include "hba/core/lie.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::test {
namespace {

std::vector<Vec3> scenePoints() {
  std::vector<Vec3> points;
  for (double x = -1.0; x <= 6.0; x += 0.05) {
    for (double y = -4.0; y <= 4.0; y += 0.05) points.emplace_back(x, y, 0.0);
  }
  for (double y = -3.0; y <= 3.0; y += 0.05) {
    for (double z = 0.05; z <= 2.0; z += 0.05) points.emplace_back(5.0, y, z);
  }
  return points;
}

}  // namespace

std::vector<Pose> syntheticPoses() {
  std::vector<Pose> poses;
  for (int i = 0; i < 4; ++i) {
    poses.emplace_back(Mat3(so3Exp(Vec3(0, 0, 0.1 * i))), Vec3(0.5 * i, 0.3 * i, 1.0));
  }
  return poses;
}

std::vector<PointCloud> syntheticScans(const std::vector<Pose>& poses) {
  const std::vector<Vec3> world = scenePoints();
  std::vector<PointCloud> scans(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose to_sensor = poses[i].inverse();
    for (const Vec3& p : world) scans[i].add((to_sensor * p).cast<float>(), 1.0f);
  }
  return scans;
}

void writeSyntheticDataset(const std::filesystem::path& dir, const std::vector<Pose>& poses) {
  std::filesystem::create_directories(dir / "Scans");
  const std::vector<PointCloud> scans = syntheticScans(poses);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06zu.pcd", i);
    io::writePcd(dir / "Scans" / name, scans[i]);
  }
  Trajectory trajectory;
  trajectory.poses = poses;
  io::writePoses(dir / "odom_poses.txt", trajectory, io::PoseFormat::Kitti);
}

}  // namespace hba::test
