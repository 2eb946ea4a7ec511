// ROS 1 bags written by Debian's python3-rosbag (not by hba) read back:
// every chunk compression, other field layouts and byte orders, poses
// interpolated at the scans' stamps.
#include <gtest/gtest.h>

#include <cmath>

#include "bag_fixture.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/rec/recording.hpp"
#include "hba/rec/ros1_bag.hpp"

namespace hba::rec {
namespace {
using test::angleBetween;

void expectSameScan(const PointCloud& read, const PointCloud& written) {
  ASSERT_EQ(read.size(), written.size());
  ASSERT_TRUE(read.hasIntensity());
  for (std::size_t p = 0; p < read.size(); ++p) {
    ASSERT_EQ(read.points[p], written.points[p]) << "point " << p;
    ASSERT_EQ(read.intensity[p], written.intensity[p]) << "point " << p;
  }
}

class Ros1BagCompression : public ::testing::TestWithParam<const char*> {};

TEST_P(Ros1BagCompression, ReadsWhatRosbagWrote) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", std::string("--compression ") + GetParam());

  const Ros1Bag bag = Ros1Bag::open(dir / "run.bag");
  std::size_t clouds = 0;
  for (const Ros1Connection& c : bag.connections()) {
    if (c.topic == "/cloud_registered_body") {
      EXPECT_EQ(c.type, "sensor_msgs/PointCloud2");
      EXPECT_NE(c.definition.find("PointField[] fields"), std::string::npos);
      clouds += bag.messageCount(c.id);
    }
  }
  EXPECT_EQ(clouds, 12u);

  const Recording recording = Recording::open(dir / "run.bag");
  EXPECT_EQ(recording.cloudTopic(), "/cloud_registered_body");
  EXPECT_EQ(recording.poseTopic(), "/Odometry");
  EXPECT_EQ(recording.cloudFrame(), "body");
  EXPECT_TRUE(recording.warnings().empty());
  ASSERT_EQ(recording.size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_NEAR(recording.trajectory().stamps[k], folder.stamps[k], 1e-6);
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
    expectSameScan(recording.loadScan(k), folder.scans[k]);
  }
}

INSTANTIATE_TEST_SUITE_P(Chunks, Ros1BagCompression, ::testing::Values("none", "lz4", "bz2"));

TEST(Ros1Bag, ReadsFloat64BigEndianCloudsWithOtherFields) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 4);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--layout float64 --big-endian");
  const Recording recording = Recording::open(dir / "run.bag");
  EXPECT_EQ(recording.cloudFields(), (std::vector<std::string>{"x", "y", "z", "ring", "intensity"}));
  ASSERT_EQ(recording.size(), 4u);
  // float32 -> float64 -> float32 is exact; the intensities are whole numbers.
  for (std::size_t k = 0; k < 4; ++k) expectSameScan(recording.loadScan(k), folder.scans[k]);
}

// Ouster's layout: each point's time as uint32 ns since the stamp (field t).
TEST(Ros1Bag, RawSweepsAreDeskewedByTheRecordedMotion) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 5);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--layout ouster");
  const Recording recording = Recording::open(dir / "run.bag");
  const PointCloud raw = recording.loadScan(2);
  ASSERT_EQ(raw.time.size(), raw.size());
  EXPECT_EQ(raw.time[1], std::floor(1e8 / static_cast<double>(raw.size())));

  const io::Dataset dataset = io::Dataset::open(dir / "run.bag");
  ASSERT_TRUE(dataset.pointTimes().has_value());
  EXPECT_EQ(dataset.pointTimes()->describe(), "ns since the scan's stamp");
  const PointCloud deskewed = dataset.loadScan(2);
  ASSERT_EQ(deskewed.size(), raw.size());
  // The last point, seen ~0.1 s after the stamp, moves by the folder's
  // motion over that time (the poses interpolated between scans 2 and 3).
  const std::size_t last = raw.size() - 1;
  const double since = raw.time[last] * 1e-9;
  const Pose motion = relative(folder.poses[2], interpolate(folder.poses[2], folder.poses[3], since / 0.1));
  const Vec3 expected = motion * raw.points[last].cast<double>();
  EXPECT_LT((deskewed.points[last].cast<double>() - expected).norm(), 1e-3);
  EXPECT_GT((deskewed.points[last] - raw.points[last]).norm(), 0.01);  // it did move
  EXPECT_LT((deskewed.points[0] - raw.points[0]).norm(), 1e-4);  // the first point, at the stamp, did not
}

// Livox's own message (livox_ros_driver/CustomMsg), as FAST-LIO2 records
// /livox/lidar: the same points, reflectivity as intensity, offset_time as
// each point's time; the driver's all-zero point left out.
TEST(Ros1Bag, ReadsLivoxCustomMessages) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 4);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "livox.bag", "--layout livox");
  const Recording recording = Recording::open(dir / "livox.bag");
  EXPECT_EQ(recording.cloudType(), "livox_ros_driver/CustomMsg");
  ASSERT_EQ(recording.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const PointCloud scan = recording.loadScan(k);
    expectSameScan(scan, folder.scans[k]);
    ASSERT_EQ(scan.time.size(), scan.size());
    EXPECT_EQ(scan.time.back(), std::floor(1e8 * static_cast<double>(scan.size() - 1) / scan.size()));
  }
  const io::Dataset dataset = io::Dataset::open(dir / "livox.bag");
  ASSERT_TRUE(dataset.pointTimes().has_value());
  EXPECT_EQ(dataset.pointTimes()->describe(), "ns since the scan's stamp");
}

// A trajectory only in /tf (odom -> body, beside other pairs): named with
// --pose-topic /tf and --tf-frames, never taken unasked.
TEST(Ros1Bag, ReadsATrajectoryFromTfBetweenTwoFrames) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "tf.bag", "--pose-type tf");
  const auto errorOf = [&](const RecordingOptions& options) {
    try {
      Recording::open(dir / "tf.bag", options);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(errorOf({}).find("no trajectory"), std::string::npos);
  RecordingOptions options;
  options.pose_topic = "/tf";
  const std::string pairs = errorOf(options);
  EXPECT_NE(pairs.find("2 pairs of frames"), std::string::npos) << pairs;
  EXPECT_NE(pairs.find("odom -> body  6 transforms"), std::string::npos) << pairs;
  EXPECT_NE(pairs.find("body -> wheel  3 transforms"), std::string::npos) << pairs;
  options.tf_parent = "odom";
  options.tf_child = "base_link";
  EXPECT_NE(errorOf(options).find("places no base_link in odom"), std::string::npos);
  options.tf_child = "body";
  const Recording recording = Recording::open(dir / "tf.bag", options);
  ASSERT_EQ(recording.size(), 6u);
  EXPECT_EQ(recording.poseFrame(), "body");
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
  }
}

TEST(Ros1Bag, InterpolatesPosesAtTheScansStamps) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 10);
  // Each pose stamped 30 ms after its scan: scan k lies 70 % of the way
  // from pose k-1 to pose k, and scan 0 before the trajectory.
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--pose-shift 0.03");
  const Recording recording = Recording::open(dir / "run.bag");
  ASSERT_EQ(recording.size(), 9u);
  ASSERT_EQ(recording.warnings().size(), 1u);
  EXPECT_NE(recording.warnings().front().find("1 of 10 scans lie outside the trajectory"), std::string::npos)
      << recording.warnings().front();
  for (std::size_t k = 1; k < 10; ++k) {
    const Pose& a = folder.poses[k - 1];
    const Pose& b = folder.poses[k];
    const Pose& got = recording.trajectory().poses[k - 1];
    EXPECT_NEAR(recording.trajectory().stamps[k - 1], folder.stamps[k], 1e-6);
    EXPECT_LT((got.t - (0.3 * a.t + 0.7 * b.t)).norm(), 1e-6);
    // On the arc from a to b, 70 % of the way.
    EXPECT_NEAR(angleBetween(a, got), 0.7 * angleBetween(a, b), 1e-6);
    EXPECT_NEAR(angleBetween(got, b), 0.3 * angleBetween(a, b), 1e-6);
  }
}

TEST(Ros1Bag, ReadsPoseStampedTrajectoriesAndTakesAnOffset) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--pose-type posestamped --pose-shift 0.5");
  RecordingOptions options;
  options.time_offset = 0.5;  // the poses' clock runs 0.5 s ahead
  const Recording recording = Recording::open(dir / "run.bag", options);
  EXPECT_EQ(recording.poseTopic(), "/pose");
  ASSERT_EQ(recording.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-6);
}

// PoseWithCovarianceStamped, and a nav_msgs/Path republished whole at every
// scan (only its last message is the trajectory).
class Ros1BagPoseTypes : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(Ros1BagPoseTypes, ReadsTheTrajectory) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 7);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", std::string("--pose-type ") + GetParam().first);
  const Recording recording = Recording::open(dir / "run.bag");
  EXPECT_EQ(recording.poseTopic(), GetParam().second);
  ASSERT_EQ(recording.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(Types, Ros1BagPoseTypes,
                         ::testing::Values(std::make_pair("posecov", "/pose"),
                                           std::make_pair("path", "/path")));

TEST(Ros1Bag, KeepsKeyframesByDistanceOrTurn) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 30);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "");
  for (const auto& [distance, angle] :
       {std::make_pair(0.5, 0.0), std::make_pair(0.0, 10.0), std::make_pair(0.6, 9.0)}) {
    RecordingOptions options;
    options.keyframe_distance = distance;
    options.keyframe_angle = angle;
    const Recording recording = Recording::open(dir / "run.bag", options);
    ASSERT_GT(recording.size(), 3u);
    ASSERT_LT(recording.size(), 30u);
    // Each kept scan is the first of the written ones far or turned enough
    // from the kept one before it; the scans between are not.
    std::size_t k = 0;
    for (std::size_t i = 0; i < 30 && k < recording.size(); ++i) {
      const bool is_kept = (folder.poses[i].t - recording.trajectory().poses[k].t).norm() < 1e-9;
      if (k > 0) {
        const Pose& last = recording.trajectory().poses[k - 1];
        const double moved = (folder.poses[i].t - last.t).norm();
        const double turned = angleBetween(last, folder.poses[i]) * 180.0 / M_PI;
        const bool enough = (distance > 0 && moved >= distance) || (angle > 0 && turned >= angle);
        EXPECT_EQ(is_kept, enough) << "scan " << i << " keyframe " << k;
      }
      if (is_kept) {
        expectSameScan(recording.loadScan(k), folder.scans[i]);
        ++k;
      }
    }
    EXPECT_EQ(k, recording.size());
  }
}

TEST(Ros1Bag, TfStaticJoinsTheCloudsFrameToThePosesBody) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 5);
  // LiDAR 0.1 m ahead of and 0.2 m above the body, turned 90 deg about z.
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag",
                    "--tf-static '0.1 0 0.2 0 0 0.7071067811865476 0.7071067811865476'");
  const Pose lidar_in_body(Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())), Vec3(0.1, 0.0, 0.2));
  const Recording recording = Recording::open(dir / "run.bag");
  EXPECT_EQ(recording.cloudFrame(), "lidar");
  EXPECT_EQ(recording.poseFrame(), "body");
  ASSERT_TRUE(recording.staticExtrinsic().has_value());
  EXPECT_LT((recording.staticExtrinsic()->t - lidar_in_body.t).norm(), 1e-9);
  EXPECT_LT(angleBetween(*recording.staticExtrinsic(), lidar_in_body), 1e-9);
  // The dataset's poses are the LiDAR's; its outputs can name the body's too.
  const io::Dataset dataset = io::Dataset::open(dir / "run.bag");
  EXPECT_EQ(dataset.inputFrame(), "body");
  for (std::size_t k = 0; k < 5; ++k) {
    const Pose expected = folder.poses[k] * lidar_in_body;
    EXPECT_LT((dataset.trajectory().poses[k].t - expected.t).norm(), 1e-9);
    EXPECT_LT(angleBetween(dataset.trajectory().poses[k], expected), 1e-9);
  }
}

// The message of the hba::Error opening `path` as a dataset throws ("" if none).
std::string datasetError(const std::filesystem::path& path, const io::DatasetOverrides& overrides = {}) {
  try {
    io::Dataset::open(path, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A raw recording (no trajectory topic) with an odometry's stamped pose
// file, as KISS-ICP writes it: each scan's pose interpolated from the file.
TEST(Ros1Bag, AStampedPoseFileIsTheTrajectoryOfARecordingWithoutOne) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 8);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "raw.bag", "--pose-type none");
  // Poses at every other scan's stamp, 20 ms late: the scans between are interpolated.
  Trajectory odometry;
  for (std::size_t k = 0; k < 8; k += 2) {
    odometry.poses.push_back(folder.poses[k]);
    odometry.stamps.push_back(folder.stamps[k] + 0.02);
  }
  io::writePoses(dir / "odometry_tum.txt", odometry, io::PoseFormat::Tum);
  EXPECT_NE(datasetError(dir / "raw.bag").find("no trajectory"), std::string::npos);
  io::DatasetOverrides overrides;
  overrides.poses_file = dir / "odometry_tum.txt";
  const io::Dataset dataset = io::Dataset::open(dir / "raw.bag", overrides);
  ASSERT_EQ(dataset.size(), 6u);  // the first scan and the last lie outside the poses
  EXPECT_NEAR(dataset.trajectory().stamps[0], folder.stamps[1], 1e-6);
  const Pose expected = interpolate(folder.poses[0], folder.poses[2], 0.4);  // scan 1: 80 of 200 ms
  EXPECT_LT((dataset.trajectory().poses[0].t - expected.t).norm(), 1e-6);
  EXPECT_LT(angleBetween(dataset.trajectory().poses[0], expected), 1e-6);

  // A pose topic cannot be named beside it.
  overrides.recording.pose_topic = "/Odometry";
  const std::string error = datasetError(dir / "raw.bag", overrides);
  EXPECT_NE(error.find("odometry_tum.txt"), std::string::npos) << error;
  EXPECT_NE(error.find("--pose-topic"), std::string::npos) << error;
}

io::DatasetOverrides keyframesEvery30cm() {
  io::DatasetOverrides overrides;
  overrides.recording.keyframe_distance = 0.3;
  return overrides;
}

// An earlier run's keyframe poses, given back: the same keyframes, at those poses exactly.
TEST(Ros1Bag, KeyframePosesGivenBackKeepTheirKeyframes) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "");
  io::DatasetOverrides overrides = keyframesEvery30cm();
  const io::Dataset first = io::Dataset::open(dir / "run.bag", overrides);
  ASSERT_LT(first.size(), 12u);
  // "Optimized" poses half as far apart: chosen from scratch, fewer would be keyframes.
  Trajectory moved = first.trajectory();
  for (Pose& pose : moved.poses) pose.t = moved.poses.front().t + 0.5 * (pose.t - moved.poses.front().t);
  io::writePoses(dir / "optimized_tum.txt", moved, io::PoseFormat::Tum);
  overrides.poses_file = dir / "optimized_tum.txt";
  const io::Dataset again = io::Dataset::open(dir / "run.bag", overrides);
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t k = 0; k < again.size(); ++k) {
    EXPECT_EQ(again.trajectory().stamps[k], first.trajectory().stamps[k]);
    EXPECT_LT((again.trajectory().poses[k].t - moved.poses[k].t).norm(), 1e-9);
  }
}

// Keyframes optimized, every scan's pose asked for: each covered scan moves
// as the keyframes around it did.
TEST(Ros1Bag, EveryScansPoseFollowsItsKeyframes) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "");
  const io::Dataset dataset = io::Dataset::open(dir / "run.bag", keyframesEvery30cm());
  ASSERT_LT(dataset.size(), 12u);
  const Pose shift(Quat(Eigen::AngleAxisd(0.05, Vec3::UnitZ())), Vec3(1.0, -2.0, 0.5));
  std::vector<Pose> optimized;
  for (const Pose& pose : dataset.trajectory().poses) optimized.push_back(shift * pose);
  const Trajectory every = dataset.everyScan(optimized);
  ASSERT_EQ(every.size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_NEAR(every.stamps[k], folder.stamps[k], 1e-6);
    const Pose expected = shift * folder.poses[k];
    EXPECT_LT((every.poses[k].t - expected.t).norm(), 1e-6) << k;
    EXPECT_LT(angleBetween(every.poses[k], expected), 1e-6) << k;
  }
}

TEST(Ros1Bag, ADatasetOfABagIsTheFolderItWasWrittenFrom) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 5);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--compression lz4");
  const io::Dataset from_bag = io::Dataset::open(dir / "run.bag");
  const io::Dataset from_folder = io::Dataset::open(dir / "folder");
  EXPECT_EQ(from_bag.layout(), "ros1-bag");
  ASSERT_EQ(from_bag.size(), from_folder.size());
  ASSERT_NE(from_bag.recording(), nullptr);
  for (std::size_t k = 0; k < from_bag.size(); ++k) {
    expectSameScan(from_bag.loadScan(k), from_folder.loadScan(k));
    EXPECT_LT((from_bag.trajectory().poses[k].t - from_folder.trajectory().poses[k].t).norm(), 1e-9);
  }  // A recording's options on a folder of scans are a mistake, said so.
  io::DatasetOverrides overrides;
  overrides.recording.keyframe_distance = 1.0;
  EXPECT_THROW(
      {
        try {
          io::Dataset::open(dir / "folder", overrides);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("are for recordings"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
}

}  // namespace
}  // namespace hba::rec
