// `hba optimize NEW --map MAP` and `--fixed SESSION` (issue #38): a new
// session placed in a map that stays put, its poses in the map's frame
// (here a UTM-sized one); the map file untouched; a map in another unit or
// of another place refused with what was tried, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_runs.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string hba() { return test::hbaTool(); }

const Pose kUtm(Mat3(Eigen::AngleAxisd(-0.9, Vec3::UnitZ())), Vec3(512300.0, 4120900.0, 80.0));

// Session 1's truth in the UTM-sized frame the map is written in.
fs::path truthInUtm(const fs::path& data, const fs::path& out) {
  Trajectory truth = io::readPoses(data / "session-1" / "gt_world.txt");
  for (Pose& p : truth.poses) p = kUtm * p;
  io::writePoses(out, truth, io::PoseFormat::Tum);
  return out;
}

class MapCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    // Two sessions 50 m apart along a 250 m loop, 125 m each: 75 m in common.
    test::runOk(
        hba() +
        " -q simulate --sessions 2 --frames 500 --session-frames 250 --session-shift 50 --seed 4 -o " +
        (*dir_ / "data").string());
    // The map: session 0's scans at their true poses, in a UTM-sized frame (LAS keeps its precision).
    Trajectory truth = io::readPoses(*dir_ / "data" / "session-0" / "gt_world.txt");
    for (Pose& p : truth.poses) p = kUtm * p;
    io::writePoses(*dir_ / "map_poses.txt", truth, io::PoseFormat::Tum);
    test::runOk(hba() + " -q map " + (*dir_ / "data" / "session-0").string() + " --poses " +
                (*dir_ / "map_poses.txt").string() + " --format tum -o " + map().string());
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path map() { return *dir_ / "map.las"; }
  static fs::path data(const std::string& session) { return *dir_ / "data" / session; }
  static test::TempDir* dir_;
};
test::TempDir* MapCli::dir_ = nullptr;

TEST_F(MapCli, ANewSessionComesOutInTheMapsFrameAndTheMapStaysUntouched) {
  test::TempDir dir;
  const std::string before = test::readText(map());
  test::runOk(hba() + " -q optimize " + data("session-1").string() + " --map " + map().string() +
              " --no-render -o " + (dir / "out").string());
  EXPECT_EQ(test::readText(map()), before);
  EXPECT_LT(test::ateInFrame(truthInUtm(*dir_ / "data", dir / "truth.txt"), dir / "out" / "poses_tum.txt",
                             dir.path()),
            0.02);
  const nlohmann::json report = test::readJson(dir / "out" / "report.json").at("map");
  EXPECT_GE(report.at("agreeing").get<int>(), 2);
  EXPECT_GT(report.at("tiles").get<int>(), 0);
  EXPECT_LE(report.at("refinement").at("plane_rms_after_m").get<double>(),
            report.at("refinement").at("plane_rms_before_m").get<double>());
}

TEST_F(MapCli, AFixedSessionServesAsTheMap) {
  test::TempDir dir;
  // Session 0 as an earlier run would leave it: its scans at optimized
  // (here true) poses, in the common frame.
  const fs::path fixed = dir / "fixed";
  fs::create_directories(fixed);
  fs::create_directory_symlink(data("session-0") / "pcd", fixed / "pcd");
  fs::copy_file(data("session-0") / "times.txt", fixed / "times.txt");
  io::writePoses(fixed / "pose.json", io::readPoses(data("session-0") / "gt_world.txt"), io::PoseFormat::Hba);
  const std::string poses_before = test::readText(fixed / "pose.json");
  test::runOk(hba() + " -q optimize " + data("session-1").string() + " --fixed " + fixed.string() +
              " --no-render -o " + (dir / "out").string());
  EXPECT_EQ(test::readText(fixed / "pose.json"), poses_before);
  EXPECT_LT(test::ateInFrame(data("session-1") / "gt_world.txt", dir / "out" / "poses_tum.txt", dir.path()),
            0.02);
}

TEST_F(MapCli, AMapInMillimetresIsRefusedAndNothingIsWritten) {
  test::TempDir dir;
  PointCloud cloud = io::readScan(map());
  for (Vec3f& p : cloud.points) p *= 1000.0F;
  cloud.origin *= 1000.0;
  io::writeScan(dir / "map_mm.las", cloud);
  const test::CommandResult r =
      test::runCommand(hba() + " optimize " + data("session-1").string() + " --map " +
                       (dir / "map_mm.las").string() + " --no-render -o " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("could not place this session in the map"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("in metres?"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(MapCli, AMapOfAnotherPlaceIsRefusedAndNothingIsWritten) {
  test::TempDir dir;
  // Another world (another seed), mapped by its own truth.
  test::runOk(hba() + " -q simulate --frames 200 --seed 11 -o " + (dir / "other").string());
  test::runOk(hba() + " -q map " + (dir / "other").string() + " --poses " +
              (dir / "other" / "gt.txt").string() + " -o " + (dir / "other.pcd").string());
  const test::CommandResult r =
      test::runCommand(hba() + " optimize " + data("session-1").string() + " --map " +
                       (dir / "other.pcd").string() + " --no-render -o " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("could not place this session in the map"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did not register"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(MapCli, MapAndSessionsOrPriorsTogetherAreRefused) {
  test::TempDir dir;
  const std::string session = data("session-1").string();
  const test::CommandResult both =
      test::runCommand(hba() + " optimize " + session + " --map " + map().string() + " --fixed " +
                       data("session-0").string() + " -o " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(both.exit_code, 1) << both.output;
  EXPECT_NE(both.output.find("not both"), std::string::npos) << both.output;
  const test::CommandResult folder =
      test::runCommand(hba() + " optimize " + session + " --map " + dir.path().string() + " -o " +
                       (dir / "out").string() + " 2>&1");
  EXPECT_EQ(folder.exit_code, 1) << folder.output;
  EXPECT_NE(folder.output.find("not an hba optimize output"), std::string::npos) << folder.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Issue 57 item 20: `optimize A A` and `--fixed A` on A itself ran without a word.
TEST_F(MapCli, OneSessionGivenTwiceIsRefused) {
  test::TempDir dir;
  const std::string session = data("session-1").string();
  fs::create_directory_symlink(data("session-1"), dir / "link");
  for (const std::string& second : {session, (dir / "link").string()}) {
    const test::CommandResult twice = test::runCommand(hba() + " optimize " + session + " " + second +
                                                       " -o " + (dir / "out").string() + " 2>&1");
    EXPECT_EQ(twice.exit_code, 2) << twice.output;
    EXPECT_NE(twice.output.find(second + ": this session is given twice (sessions 0 and 1"),
              std::string::npos)
        << twice.output;
    const test::CommandResult fixed = test::runCommand(hba() + " optimize " + session + " --fixed " + second +
                                                       " -o " + (dir / "out").string() + " 2>&1");
    EXPECT_EQ(fixed.exit_code, 2) << fixed.output;
    EXPECT_NE(fixed.output.find("--fixed " + second + " is the session being optimized (" + session + ")"),
              std::string::npos)
        << fixed.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace hba
