// The outputs of a recording read back (issue 57 items 13 and 16): `hba view
// OUT` read the recording as a text pose file, and `--map OUT` of a keyframed
// run opened every cloud for the keyframes' poses. The run's report.json now
// records how the recording was read, and both read it so. The bag is
// written by Debian's python3-rosbag (skipped where it is missing).
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "bag_fixture.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }
std::string hba() { return quoted(test::cliPath()) + " -j 2 "; }

class RecordingOutputs : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const fs::path& d = dir_->path();
    // A simulated drive as the scan folder the bag writer takes: Scans/ of
    // x y z intensity PCDs, KITTI odometry, times.txt in Unix time.
    const test::CommandResult sim =
        test::runCommand(hba() + "-q simulate --frames 40 --seed 5 -o " + quoted(d / "sim"));
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    const Trajectory odometry = io::readPoses(d / "sim" / "pose.json");
    fs::create_directories(d / "folder" / "Scans");
    std::string times;
    for (std::size_t k = 0; k < odometry.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "%06zu.pcd", k);
      const PointCloud read = io::readScan(d / "sim" / "pcd" / name);
      PointCloud scan;
      for (std::size_t i = 0; i < read.size(); ++i)
        scan.add(read.points[i], read.hasIntensity() ? read.intensity[i] : 1.0f);
      io::writePcd(d / "folder" / "Scans" / name, scan);
      char stamp[32];
      std::snprintf(stamp, sizeof stamp, "%.3f\n", 1600000000.0 + 0.1 * static_cast<double>(k));
      times += stamp;
    }
    io::writePoses(d / "folder" / "odom_poses.txt", odometry, io::PoseFormat::Kitti);
    test::writeText(d / "folder" / "times.txt", times);
    writer_exit_ = test::writeBag(d / "folder", d / "run.bag");
    if (writer_exit_ != 0) return;
    // Keyframes: about one in three clouds.
    double path = 0.0;
    for (std::size_t k = 1; k < odometry.size(); ++k)
      path += (odometry.poses[k].t - odometry.poses[k - 1].t).norm();
    keyframe_distance_ = std::to_string(3.0 * path / static_cast<double>(odometry.size() - 1));
    const test::CommandResult run =
        test::runCommand(hba() + "-q optimize " + quoted(d / "run.bag") + " --keyframe-distance " +
                         keyframe_distance_ + " -o " + quoted(d / "out") + " --layers 1 --no-render");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete dir_; }
  void SetUp() override {
    if (writer_exit_ == 77) GTEST_SKIP() << "python3-rosbag is not installed";
    ASSERT_EQ(writer_exit_, 0);
  }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static test::TempDir* dir_;
  static int writer_exit_;
  static std::string keyframe_distance_;
};
test::TempDir* RecordingOutputs::dir_ = nullptr;
int RecordingOutputs::writer_exit_ = -1;
std::string RecordingOutputs::keyframe_distance_;

std::size_t posesIn(const fs::path& file) { return io::readPoses(file).size(); }

TEST_F(RecordingOutputs, TheReportRecordsHowTheRecordingWasRead) {
  const nlohmann::json report = nlohmann::json::parse(test::readText(path("out") / "report.json"));
  const nlohmann::json& recording = report["input"]["recording"];
  EXPECT_EQ(recording["cloud_topic"], "/cloud_registered_body") << recording.dump();
  EXPECT_EQ(recording["pose_topic"], "/Odometry") << recording.dump();
  EXPECT_DOUBLE_EQ(recording["keyframe_distance"].get<double>(), std::stod(keyframe_distance_));
  const std::size_t keyframes = posesIn(path("out") / "pose.json");
  EXPECT_LT(keyframes, 30u);
  EXPECT_EQ(report["input"]["scans"], keyframes);
}

TEST_F(RecordingOutputs, ViewOfTheOutputReadsTheRecordingsKeyframes) {
  fs::remove(path("out") / "report.html");
  const test::CommandResult viewed = test::runCommand(hba() + "view " + quoted(path("out")));
  ASSERT_EQ(viewed.exit_code, 0) << viewed.output;
  EXPECT_EQ(test::readText(path("out") / "report.html").rfind("<!DOCTYPE html>", 0), 0u);
}

TEST_F(RecordingOutputs, MapOfTheOutputUsesTheKeyframesTheRunKept) {
  // The recording placed in the map of its own earlier run (as a new
  // session would be): the map is the run's keyframes at their poses.
  const test::CommandResult mapped =
      test::runCommand(hba() + "-q optimize " + quoted(path("run.bag")) + " --keyframe-distance " +
                       keyframe_distance_ + " --map " + quoted(path("out")) + " -o " + quoted(path("again")) +
                       " --layers 1 --no-render --no-report-page");
  EXPECT_EQ(mapped.output.find("differ in number"), std::string::npos) << mapped.output;
  ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
  EXPECT_EQ(posesIn(path("again") / "pose.json"), posesIn(path("out") / "pose.json"));
}

TEST_F(RecordingOutputs, AnOlderReportOfAKeyframedRunIsRefusedSayingWhy) {
  // An output of an hba that did not record the keyframes.
  fs::create_directories(path("old"));
  fs::copy_file(path("out") / "pose.json", path("old") / "pose.json", fs::copy_options::overwrite_existing);
  nlohmann::json report = nlohmann::json::parse(test::readText(path("out") / "report.json"));
  report["input"].erase("recording");
  test::writeText(path("old") / "report.json", report.dump(2));
  const std::string why =
      "the run kept keyframes of the recording (or read other topics), and its report.json";
  const test::CommandResult viewed = test::runCommand(hba() + "view " + quoted(path("old")));
  EXPECT_EQ(viewed.exit_code, 1) << viewed.output;
  EXPECT_NE(
      viewed.output.find((path("old") / "pose.json").string() + ": " +
                         std::to_string(posesIn(path("old") / "pose.json")) + " poses for the 40 scans of "),
      std::string::npos)
      << viewed.output;
  EXPECT_NE(viewed.output.find(why), std::string::npos) << viewed.output;
  const test::CommandResult mapped =
      test::runCommand(hba() + "-q optimize " + quoted(path("run.bag")) + " --map " + quoted(path("old")) +
                       " -o " + quoted(path("never")));
  EXPECT_EQ(mapped.exit_code, 1) << mapped.output;
  EXPECT_NE(mapped.output.find(why), std::string::npos) << mapped.output;
  EXPECT_FALSE(fs::exists(path("never")));
}

}  // namespace
}  // namespace hba
