#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "hba/ba/window_ba.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/voxel/downsample.hpp"
#include "test_support.hpp"

namespace hba::ba {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Ten consecutive Livox scans of the hku1 campus walk with their odometry
// poses: a real window must end with a lower cost and sharper planes.
TEST(RealWindow, Hku1TenScansImproveConsistency) {
  const std::filesystem::path root = test::sharedDataDir() / "hku1";
  if (!std::filesystem::exists(root / "odom_poses.txt")) GTEST_SKIP() << "no " << root;
  const Trajectory odom = io::readPoses(root / "odom_poses.txt", io::PoseFormat::Kitti);

  constexpr int kFirst = 150;
  constexpr int kCount = 10;
  std::vector<PointCloud> scans;
  std::vector<Pose> initial;
  for (int i = kFirst; i < kFirst + kCount; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.pcd", i);
    scans.push_back(voxel::downsample(io::readPcd(root / "Scans" / name), 0.1));
    initial.push_back(odom.poses.at(i));
  }
  std::vector<const PointCloud*> ptrs;
  for (const PointCloud& s : scans) ptrs.push_back(&s);

  BaSettings settings;
  settings.planes.voxel_size = 1.0;  // small campus scene (the paper: 1-2 m indoors)
  const BaResult result = optimizeWindow(ptrs, initial, settings);

  const double rms_before = median(result.plane_rms_initial);
  const double rms_after = median(result.plane_rms_final);
  std::printf(
      "hku1 %d..%d: planes %zu, points %zu, rounds %d, iterations %d\n"
      "  cost (last association) %.6g -> %.6g, first association %.6g\n"
      "  median plane RMS %.4f m -> %.4f m\n",
      kFirst, kFirst + kCount - 1, result.num_planes, result.num_plane_points, result.rounds,
      result.iterations, result.last_association_initial_cost, result.final_cost, result.initial_cost,
      rms_before, rms_after);

  ASSERT_GT(result.num_planes, 50u);
  EXPECT_LT(result.final_cost, 0.97 * result.last_association_initial_cost);
  EXPECT_LT(rms_after, rms_before);
  EXPECT_TRUE(result.hessian.allFinite());
}

}  // namespace
}  // namespace hba::ba
