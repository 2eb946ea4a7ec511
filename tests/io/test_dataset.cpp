// Dataset discovery on the checked-in fixture layouts: which scans, which
// trajectory, in which order, and the pose conversions each layout implies.
#include <gtest/gtest.h>

#include <string>

#include "hba/io/dataset.hpp"
#include "test_dataset_support.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using test::datasetDir;

TEST(Dataset, HbaLayoutOrdersPlainNamesNumerically) {
  const Dataset d = Dataset::open(datasetDir("hba_plain"));
  EXPECT_EQ(d.layout(), "hba");
  EXPECT_EQ(d.poseFormat(), PoseFormat::Hba);
  EXPECT_EQ(d.scansDir().filename(), "pcd");
  EXPECT_EQ(d.posesFile().filename(), "pose.json");
  ASSERT_EQ(d.size(), 11u);
  EXPECT_EQ(d.scanPath(2).filename(), "2.pcd");  // lexical order would put 10.pcd here
  EXPECT_EQ(d.scanPath(10).filename(), "10.pcd");
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(d.trajectory().poses[i].t.x(), double(i));
  EXPECT_FALSE(d.trajectory().hasStamps());
}

TEST(Dataset, HbaLayoutWithZeroPaddedNames) {
  test::TempDir dir;
  test::makeScans(dir / "pcd", {"00000.pcd", "00001.pcd", "00002.pcd"});
  test::writeText(dir / "pose.json", test::hbaPoseLines(3));
  const Dataset d = Dataset::open(dir.path());
  EXPECT_EQ(d.layout(), "hba");
  EXPECT_EQ(d.size(), 3u);
  EXPECT_EQ(d.scanPath(1).filename(), "00001.pcd");
}

TEST(Dataset, FastLioLayoutPrefersOdometryAndReadsTimes) {
  const Dataset d = Dataset::open(datasetDir("fastlio_scans"));
  EXPECT_EQ(d.layout(), "scans");
  EXPECT_EQ(d.scansDir().filename(), "Scans");
  EXPECT_EQ(d.posesFile().filename(), "odom_poses.txt");
  EXPECT_EQ(d.poseFormat(), PoseFormat::Kitti);
  EXPECT_TRUE(test::anyNoteMentions(d, "optimized_poses.txt"));
  ASSERT_TRUE(d.trajectory().hasStamps());
  EXPECT_EQ(d.timesFile().filename(), "times.txt");
  EXPECT_DOUBLE_EQ(d.trajectory().stamps[2], 101.0);
  EXPECT_DOUBLE_EQ(d.trajectory().poses[2].t.x(), 2.0);
}

TEST(Dataset, KittiLayoutTurnsCameraPosesIntoLidarPoses) {
  const Dataset d = Dataset::open(datasetDir("kitti_odometry"));
  EXPECT_EQ(d.layout(), "kitti");
  EXPECT_EQ(d.calibrationFile().filename(), "calib.txt");
  ASSERT_EQ(d.size(), 3u);
  // The camera moves along its z (forward), which is the LiDAR's x; the world
  // is the first LiDAR frame, so the LiDAR moves along world x unrotated.
  for (std::size_t i = 0; i < d.size(); ++i) {
    const Pose& pose = d.trajectory().poses[i];
    EXPECT_LT((pose.t - Vec3(double(i), 0, 0)).norm(), 1e-12) << "pose " << i;
    EXPECT_LT(pose.q.angularDistance(Quat::Identity()), 1e-12) << "pose " << i;
  }
}

TEST(Dataset, ExplicitPosesAreTakenAsLidarPoses) {
  DatasetOverrides overrides;
  overrides.poses_file = "poses.txt";  // relative: found in the dataset folder
  const Dataset d = Dataset::open(datasetDir("kitti_odometry"), overrides);
  EXPECT_TRUE(d.calibrationFile().empty());
  EXPECT_EQ(d.posesFile(), datasetDir("kitti_odometry") / "poses.txt");
  EXPECT_LT((d.trajectory().poses[2].t - Vec3(0, 0, 2)).norm(), 1e-12);
}

TEST(Dataset, OverridesWin) {
  const fs::path root = datasetDir("fastlio_scans");
  DatasetOverrides overrides;
  overrides.poses_file = root / "optimized_poses.txt";
  Dataset d = Dataset::open(root, overrides);
  EXPECT_EQ(d.posesFile().filename(), "optimized_poses.txt");
  EXPECT_DOUBLE_EQ(d.trajectory().poses[1].t.y(), 0.5);

  overrides.scans_dir = root / "Scans";
  d = Dataset::open(root, overrides);
  EXPECT_EQ(d.layout(), "explicit");

  overrides.pose_format = PoseFormat::Hba;
  test::expectErrorMentioning([&] { Dataset::open(root, overrides); },
                              {"optimized_poses.txt", "line 1", "expected 7"});
}

TEST(Dataset, OpeningReadsNoScanButLoadingNamesTheBadFile) {
  const Dataset d = Dataset::open(datasetDir("garbage_scans"));
  ASSERT_EQ(d.size(), 2u);
  test::expectErrorMentioning([&] { d.loadScan(1); }, {"000001.pcd"});
}

TEST(Dataset, LoadsScansInOrder) {
  const Dataset d = Dataset::open(datasetDir("fastlio_scans"));
  for (std::size_t i = 0; i < d.size(); ++i) {
    const PointCloud cloud = d.loadScan(i);
    EXPECT_EQ(cloud.size(), 4 + i);  // the fixtures hold 4, 5, 6 points
    EXPECT_FLOAT_EQ(cloud.points[0].x(), float(i));
  }
}

}  // namespace
}  // namespace hba::io
