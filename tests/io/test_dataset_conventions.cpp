// Dataset discovery of the inputs that used to give silent errors: scans
// named by time, --times, inverted poses, another body frame, KITTI
// calibration for an explicit pose file, scans saved in the world frame.
#include <gtest/gtest.h>

#include <string>

#include "hba/io/dataset.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "test_dataset_support.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

// TUM lines at the given stamps, pose i at x = i.
std::string tumLines(const std::vector<double>& stamps) {
  std::string text;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    text += std::to_string(stamps[i]) + " " + std::to_string(i) + " 0 0 0 0 0 1\n";
  }
  return text;
}

TEST(DatasetTimeNames, ScansNamedByTimeAreOrderedByTimeAndPairedByTime) {
  test::TempDir dir;
  // Listed out of order on purpose; 9 digits of fraction, as bag exporters write.
  test::makeScans(dir / "pcd", {"1577836980.200000000.pcd", "1577836980.000000000.pcd",
                                "1577836980.100000000.pcd", "1577836980.300000000.pcd"});
  // Odometry starts one scan late and runs one pose longer, stamped 3 ms off.
  test::writeText(dir / "traj.tum",
                  tumLines({1577836980.103, 1577836980.203, 1577836980.303, 1577836980.403}));
  DatasetOverrides overrides;
  overrides.poses_file = dir / "traj.tum";
  const Dataset d = Dataset::open(dir.path(), overrides);
  ASSERT_EQ(d.size(), 3u);  // the first scan has no pose within half a period
  EXPECT_EQ(d.scanPath(0).filename(), "1577836980.100000000.pcd");
  EXPECT_EQ(d.scanPath(2).filename(), "1577836980.300000000.pcd");
  EXPECT_EQ(d.trajectory().poses[0].t.x(), 0.0);
  EXPECT_EQ(d.trajectory().poses[2].t.x(), 2.0);
  EXPECT_EQ(d.stampsSource(), "trajectory");
  EXPECT_TRUE(test::anyNoteMentions(d, "left out"));
}

TEST(DatasetTimeNames, NanosecondNamesGiveStampsToAnUnstampedTrajectory) {
  test::TempDir dir;
  test::makeScans(dir / "Scans", {"1577836980100000000.pcd", "1577836980000000000.pcd"});
  test::writeText(dir / "odom_poses.txt", test::kittiPoseLines(2));
  const Dataset d = Dataset::open(dir.path());
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.scanPath(0).filename(), "1577836980000000000.pcd");
  EXPECT_EQ(d.stampsSource(), "scan names");
  EXPECT_NEAR(d.trajectory().stamps[1] - d.trajectory().stamps[0], 0.1, 1e-6);
}

TEST(DatasetTimeNames, MillisecondAndMicrosecondNamesAreTimes) {
  for (const auto& [a, b] : {std::pair<std::string, std::string>{"1577836980100.pcd", "1577836980000.pcd"},
                             {"1577836980100000.pcd", "1577836980000000.pcd"}}) {
    test::TempDir dir;
    test::makeScans(dir / "Scans", {a, b});
    test::writeText(dir / "odom_poses.txt", test::kittiPoseLines(2));
    const Dataset d = Dataset::open(dir.path());
    EXPECT_EQ(d.scanPath(0).filename(), b);
    EXPECT_NEAR(d.trajectory().stamps[0], 1577836980.0, 1e-6);
    EXPECT_NEAR(d.trajectory().stamps[1] - d.trajectory().stamps[0], 0.1, 1e-6);
  }
}

TEST(DatasetTimeNames, TrajectoryOnAnotherClockIsAnErrorThatSaysSo) {
  test::TempDir dir;
  test::makeScans(dir / "pcd", {"1577836980.000000000.pcd", "1577836980.100000000.pcd"});
  test::writeText(dir / "traj.tum", tumLines({0.0, 0.1}));
  DatasetOverrides overrides;
  overrides.poses_file = dir / "traj.tum";
  test::expectErrorMentioning([&] { Dataset::open(dir.path(), overrides); },
                              {"only 0 of 2 scans", "same clock"});
}

// Numbered scans with a times.txt, odometry at twice the scan rate: paired by time.
TEST(DatasetTimes, TrajectoryAtAnotherRateIsPairedByTheScansTimes) {
  test::TempDir dir;
  test::makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", "000002.pcd"});
  test::writeText(dir / "times.txt", "10.0\n10.1\n10.2\n");
  test::writeText(dir / "traj.tum", tumLines({9.95, 10.0, 10.05, 10.1, 10.15, 10.2, 10.25}));
  DatasetOverrides overrides;
  overrides.poses_file = dir / "traj.tum";
  const Dataset d = Dataset::open(dir.path(), overrides);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d.trajectory().poses[0].t.x(), 1.0);
  EXPECT_EQ(d.trajectory().poses[2].t.x(), 5.0);
  EXPECT_TRUE(test::anyNoteMentions(d, "poses have no scan"));
}

// Some exporters write TUM stamps in nanoseconds; they still pair by time.
TEST(DatasetTimes, NanosecondStampsAreReadAsSeconds) {
  test::TempDir dir;
  test::makeScans(dir / "pcd", {"1577836980.000000000.pcd", "1577836980.100000000.pcd"});
  test::writeText(dir / "traj.tum", "1577836980000000000 0 0 0 0 0 0 1\n1577836980100000000 1 0 0 0 0 0 1\n");
  DatasetOverrides overrides;
  overrides.poses_file = dir / "traj.tum";
  const Dataset d = Dataset::open(dir.path(), overrides);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d.trajectory().stamps[1], 1577836980.1, 1e-6);
  EXPECT_TRUE(test::anyNoteMentions(d, "in ns"));
}

TEST(DatasetTimes, StampUnitsAreRecognized) {
  const auto seconds = [](std::vector<double> stamps, const std::string& unit) {
    EXPECT_EQ(stampsToSeconds(stamps), unit);
    return stamps;
  };
  EXPECT_NEAR(seconds({1577836980100.0, 1577836980200.0}, "ms")[1], 1577836980.2, 1e-6);
  EXPECT_NEAR(seconds({1577836980100000.0, 1577836980200000.0}, "us")[1], 1577836980.2, 1e-6);
  EXPECT_NEAR(seconds({0.0, 1e8, 2e8}, "ns")[2], 0.2, 1e-12);  // ns from the start
  EXPECT_NEAR(seconds({0.0, 1e5, 2e5}, "us")[2], 0.2, 1e-12);
  EXPECT_NEAR(seconds({1577836980.1, 1577836980.2}, "")[1], 1577836980.2, 1e-6);
  EXPECT_NEAR(seconds({0.0, 60.0, 120.0}, "")[2], 120.0, 1e-12);  // sparse keyframes in seconds
}

TEST(DatasetTimes, TimesThatGoBackwardsCannotBePairedByTime) {
  test::TempDir dir;
  test::makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", "000002.pcd"});
  test::writeText(dir / "stamps.txt", "10.0\n10.2\n10.1\n");
  test::writeText(dir / "traj.tum", tumLines({10.0, 10.1, 10.2}));
  DatasetOverrides overrides;
  overrides.poses_file = dir / "traj.tum";
  overrides.times_file = dir / "stamps.txt";
  test::expectErrorMentioning([&] { Dataset::open(dir.path(), overrides); },
                              {"stamps.txt", "do not increase at line 3"});
}

TEST(DatasetTimes, TimesFlagSuppliesStampsAndMustMatchTheScans) {
  test::TempDir dir;
  test::makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", "000002.pcd"});
  test::writeText(dir / "odom_poses.txt", test::kittiPoseLines(3));
  test::writeText(dir / "stamps.txt", "10.0\n10.1\n10.2\n");
  DatasetOverrides overrides;
  overrides.times_file = dir / "stamps.txt";
  const Dataset d = Dataset::open(dir.path(), overrides);
  EXPECT_EQ(d.stampsSource(), "times file");
  EXPECT_EQ(d.trajectory().stamps[2], 10.2);
  test::writeText(dir / "backwards.txt", "10.0\n10.2\n10.1\n");
  overrides.times_file = dir / "backwards.txt";
  EXPECT_TRUE(test::anyNoteMentions(Dataset::open(dir.path(), overrides), "do not increase at scan 2"));
  test::writeText(dir / "short.txt", "10.0\n10.1\n");
  overrides.times_file = dir / "short.txt";
  test::expectErrorMentioning([&] { Dataset::open(dir.path(), overrides); },
                              {"short.txt", "2 timestamps for 3 scans"});
}

TEST(DatasetConventions, InvertedPosesExtrinsicAndCalibration) {
  test::TempDir dir;
  test::makeScans(dir / "Scans", {"000000.pcd", "000001.pcd"});
  const Pose a(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())), Vec3(1, 2, 3));
  const Pose b(Quat(Eigen::AngleAxisd(-0.7, Vec3(1, 1, 0).normalized())), Vec3(-4, 5, 0.5));
  writePoses(dir / "odom_poses.txt", Trajectory{{a, b}, {}}, PoseFormat::Kitti);

  DatasetOverrides inverted;
  inverted.invert_poses = true;
  const Dataset d1 = Dataset::open(dir.path(), inverted);
  EXPECT_LT((d1.trajectory().poses[1].matrix() - b.inverse().matrix()).norm(), 1e-12);

  // Body poses with T_body_sensor: sensor pose = body pose * extrinsic, and back.
  const Pose extrinsic(Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX())), Vec3(0.2, 0.0, -0.1));
  DatasetOverrides body;
  body.extrinsic = extrinsic;
  const Dataset d2 = Dataset::open(dir.path(), body);
  EXPECT_EQ(d2.inputFrame(), "body");
  EXPECT_LT((d2.trajectory().poses[0].matrix() - (a * extrinsic).matrix()).norm(), 1e-12);
  EXPECT_LT((d2.toInputFrame(d2.trajectory().poses)[1].matrix() - b.matrix()).norm(), 1e-12);

  // An explicit KITTI calibration: camera poses in, camera poses back out.
  DatasetOverrides camera;
  camera.calibration = test::datasetDir("kitti_odometry") / "calib.txt";
  const Dataset d3 = Dataset::open(dir.path(), camera);
  EXPECT_EQ(d3.inputFrame(), "camera");
  EXPECT_LT((d3.toInputFrame(d3.trajectory().poses)[0].matrix() - a.matrix()).norm(), 1e-12);
  camera.extrinsic = extrinsic;
  test::expectErrorMentioning([&] { Dataset::open(dir.path(), camera); }, {"--extrinsic", "--calib"});
}

TEST(DatasetConventions, ScansSavedInTheWorldAreMovedBackToTheSensor) {
  test::TempDir dir;
  const Pose pose(Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ())), Vec3(500000.0, 4000000.0, 30.0));
  PointCloud world;
  world.origin = pose.t;  // written as float64 world coordinates
  world.add(Vec3f(1.0f, 2.0f, 0.5f));
  fs::create_directories(dir / "Scans");
  writePcd(dir / "Scans" / "000000.pcd", world);
  writePoses(dir / "odom_poses.txt", Trajectory{{pose}, {}}, PoseFormat::Kitti);
  DatasetOverrides overrides;
  overrides.scans_in_world = true;
  const PointCloud scan = Dataset::open(dir.path(), overrides).loadScan(0);
  const Vec3 expected = pose.inverse() * world.world(0);
  EXPECT_LT((scan.points[0].cast<double>() - expected).norm(), 1e-5);
  EXPECT_TRUE(scan.origin.isZero());
}

}  // namespace
}  // namespace hba::io
