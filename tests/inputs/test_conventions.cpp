// Inputs in another convention are caught before optimizing, with the flag
// that fixes them, and the flags give the same result as conventional input:
// world-to-sensor poses (--invert-poses), scans saved in the world frame
// (--scans-in-world), poses of another body (--extrinsic), and KITTI camera
// poses (calib.txt; camera-frame output beside the LiDAR's).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runs.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

using PoseMap = std::function<Pose(const Pose&)>;

// A copy of the dataset in `copy` (HBA layout) with every pose mapped by
// `map_pose`; scans linked, or rewritten moved by their pose when `in_world`.
void makeCopy(const fs::path& data, const fs::path& copy, const PoseMap& map_pose, bool in_world = false) {
  const io::Dataset dataset = io::Dataset::open(data);
  fs::create_directories(copy / "pcd");
  Trajectory trajectory;
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const Pose& pose = dataset.trajectory().poses[i];
    trajectory.poses.push_back(map_pose(pose));
    const fs::path scan = copy / "pcd" / dataset.scanPath(i).filename().replace_extension(".pcd");
    if (!in_world) {
      fs::create_symlink(fs::absolute(dataset.scanPath(i)), scan);
      continue;
    }
    PointCloud cloud = dataset.loadScan(i);
    for (Vec3f& p : cloud.points) p = (pose * p.cast<double>()).cast<float>();
    io::writeScan(scan, cloud);
  }
  io::writePoses(copy / "pose.json", trajectory, io::PoseFormat::Hba);
}

class Conventions : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(test::runHba("-q simulate --frames 60 --seed 8 -o " + test::quoted(dir / "sim")).exit_code, 0);
    ASSERT_EQ(test::runOptimize(dir / "sim", dir / "reference", "--no-render", 2).exit_code, 0);
    reference = test::readOptimizedPoses(dir / "reference");
  }
  // Optimizing `data` is refused with `hint`, and with `flag` matches the reference.
  void expectCaughtAndFixed(const fs::path& data, const std::string& hint, const std::string& flag,
                            double tolerance) {
    const test::CommandResult refused = test::runOptimize(data, dir / "refused", "--no-render", 2);
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.output.find(hint), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(dir / "refused")) << "a refused run leaves no output folder";
    const test::CommandResult fixed = test::runOptimize(data, dir / "fixed", "--no-render " + flag, 2);
    ASSERT_EQ(fixed.exit_code, 0) << fixed.output;
    EXPECT_LT(test::largestTranslation(test::readOptimizedPoses(dir / "fixed"), reference), tolerance);
  }
  test::TempDir dir;
  std::vector<Pose> reference;
};

TEST_F(Conventions, InvertedPosesAreCaughtWithTheFix) {
  makeCopy(dir / "sim", dir / "inverted", [](const Pose& p) { return p.inverse(); });
  expectCaughtAndFixed(dir / "inverted", "--invert-poses", "--invert-poses", 1e-4);
}

TEST_F(Conventions, ScansInTheWorldFrameAreCaughtWithTheFix) {
  const auto same = [](const Pose& p) { return p; };
  makeCopy(dir / "sim", dir / "world", same, true);
  // The scans went through float world coordinates: millimetre agreement.
  expectCaughtAndFixed(dir / "world", "--scans-in-world", "--scans-in-world", 1e-3);
}

TEST_F(Conventions, BodyPosesWithAnExtrinsicGiveTheSensorPosesAndTheBodyPoses) {
  const Pose extrinsic(Quat(Eigen::AngleAxisd(0.2, Vec3(0.3, 1.0, 0.1).normalized())), Vec3(0.4, -0.1, 0.3));
  makeCopy(dir / "sim", dir / "body", [&](const Pose& p) { return p * extrinsic.inverse(); });
  const test::CommandResult run = test::runOptimize(
      dir / "body", dir / "out",
      "--no-render --extrinsic '0.4 -0.1 0.3 " +
          [&] {
            const Quat& q = extrinsic.q;
            return std::to_string(q.x()) + " " + std::to_string(q.y()) + " " + std::to_string(q.z()) + " " +
                   std::to_string(q.w()) + "'";
          }(),
      2);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // to_string keeps 6 decimals of the quaternion: agreement to a few 0.1 mm.
  EXPECT_LT(test::largestTranslation(test::readOptimizedPoses(dir / "out"), reference), 1e-3);
  const Trajectory body = io::readPoses(dir / "out" / "body_poses_kitti.txt");
  const std::vector<Pose> sensor = test::readOptimizedPoses(dir / "out");
  ASSERT_EQ(body.size(), sensor.size());
  EXPECT_LT(((body.poses[30] * extrinsic).t - sensor[30].t).norm(), 1e-5);
}

// A convention flag given to conventional data is caught too, and the advice
// is to drop it.
TEST_F(Conventions, AStrayConventionFlagIsCaught) {
  for (const char* flag : {"--invert-poses", "--scans-in-world"}) {
    const test::CommandResult run =
        test::runOptimize(dir / "sim", dir / "stray", std::string("--no-render ") + flag, 2);
    EXPECT_NE(run.exit_code, 0) << flag;
    EXPECT_NE(run.output.find(std::string("without ") + flag), std::string::npos) << run.output;
  }
}

// Poses of a body turned against the sensor (Ouster's sensor frame is its
// LiDAR frame turned 180 degrees about z): caught, with the turn to give.
TEST_F(Conventions, PosesOfATurnedBodyAreCaughtWithTheTurn) {
  const Pose extrinsic(Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitZ())), Vec3(0.0, 0.0, 0.036));
  makeCopy(dir / "sim", dir / "turned", [&](const Pose& p) { return p * extrinsic.inverse(); });
  expectCaughtAndFixed(dir / "turned", "--extrinsic '0 0 0 0 0 1 0'", "--extrinsic '0 0 0.036 0 0 1 0'",
                       1e-4);
}

// KITTI: camera poses and calib.txt in, camera-frame poses out that match a
// camera-frame ground truth as well as the LiDAR poses match the LiDAR's.
TEST_F(Conventions, KittiCameraPosesComeBackInTheCameraFrame) {
  // About KITTI's Tr (LiDAR -> camera): the axis change, off by half a degree.
  Mat3 axes;
  axes << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  const Pose tr(Mat3(axes * Eigen::AngleAxisd(0.01, Vec3(1, 2, 3).normalized())),
                Vec3(-0.004, -0.076, -0.27));
  const fs::path kitti = dir / "kitti";
  const io::Dataset sim = io::Dataset::open(dir / "sim");
  fs::create_directories(kitti / "velodyne");
  for (std::size_t i = 0; i < sim.size(); ++i) {
    io::writeScan(kitti / "velodyne" / sim.scanPath(i).filename().replace_extension(".bin"), sim.loadScan(i));
  }
  const auto toCamera = [&](const std::vector<Pose>& lidar) {
    Trajectory camera;
    for (const Pose& p : lidar) camera.poses.push_back(tr * p * tr.inverse());
    return camera;
  };
  io::writePoses(kitti / "poses.txt", toCamera(sim.trajectory().poses), io::PoseFormat::Kitti);
  const Trajectory gt = io::readPoses(dir / "sim" / "gt.txt");
  io::writePoses(dir / "gt_camera.txt", toCamera(gt.poses), io::PoseFormat::Kitti);
  // Without calib.txt the camera poses are caught, with the flag to give it.
  const test::CommandResult uncalibrated = test::runOptimize(kitti, dir / "refused", "--no-render", 2);
  EXPECT_NE(uncalibrated.exit_code, 0);
  EXPECT_NE(uncalibrated.output.find("--calib"), std::string::npos) << uncalibrated.output;

  const Eigen::Matrix<double, 3, 4> rows = tr.matrix().topRows<3>();
  std::string calib = "Tr:";
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) calib += " " + std::to_string(rows(r, c));
  }
  test::writeText(kitti / "calib.txt", calib + "\n");

  const test::CommandResult run = test::runOptimize(kitti, dir / "out", "--no-render", 2);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto ate = [&](const fs::path& truth, const fs::path& est) {
    const test::CommandResult eval =
        test::runHba("-q eval --gt " + test::quoted(truth) + " --est " + test::quoted(est) +
                     " --force --json " + test::quoted(dir / "e.json"));
    EXPECT_EQ(eval.exit_code, 0) << eval.output;
    return nlohmann::json::parse(test::readText(dir / "e.json")).at("ate");
  };
  const nlohmann::json camera = ate(dir / "gt_camera.txt", dir / "out" / "camera_poses_kitti.txt");
  const nlohmann::json lidar = ate(dir / "sim" / "gt.txt", dir / "out" / "poses_kitti.txt");
  EXPECT_LT(camera.at("rotation_deg").at("rmse").get<double>(), 0.05);
  EXPECT_LT(camera.at("translation_m").at("rmse").get<double>(),
            lidar.at("translation_m").at("rmse").get<double>() + 1e-3);
  // And the LiDAR poses against the camera ground truth are what the issue saw: wrong.
  EXPECT_GT(
      ate(dir / "gt_camera.txt", dir / "out" / "poses_kitti.txt").at("rotation_deg").at("rmse").get<double>(),
      10.0);
}

// Real Livox data: both wrong conventions are caught before any work.
TEST(ConventionsReal, Hku1InvertedOrInTheWorldFrameIsCaught) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  makeCopy(data, dir / "inverted", [](const Pose& p) { return p.inverse(); });
  const auto same = [](const Pose& p) { return p; };
  makeCopy(data, dir / "world", same, true);
  for (const auto& [name, hint] :
       {std::pair<std::string, std::string>{"inverted", "--invert-poses"}, {"world", "--scans-in-world"}}) {
    const test::CommandResult run = test::runOptimize(dir / name, dir / (name + "_out"), "--no-render", 2);
    EXPECT_NE(run.exit_code, 0) << name;
    EXPECT_NE(run.output.find(hint), std::string::npos) << run.output;
  }
}

}  // namespace
}  // namespace hba
