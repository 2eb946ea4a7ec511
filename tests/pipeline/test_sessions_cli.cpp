// `hba optimize A B` on sessions that start far apart in unrelated frames
// (issue #38): they meet where their paths overlap, wherever that is and
// however the frames are turned; sessions that never meet are refused with
// what was tried, and nothing is written.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_runs.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/pose_file.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string hba() { return test::hbaTool(); }

// The session's poses given in a frame turned by 120 deg of yaw and 5 of
// roll and moved 300 m: nothing about it is z up or near the other's frame.
void tiltFrame(const fs::path& session) {
  const Pose tilt(Mat3(Eigen::AngleAxisd(120.0 * M_PI / 180.0, Vec3::UnitZ()) *
                       Eigen::AngleAxisd(5.0 * M_PI / 180.0, Vec3::UnitX())),
                  Vec3(300.0, -200.0, 15.0));
  Trajectory poses = io::readPoses(session / "pose.json");
  for (Pose& p : poses.poses) p = tilt * p;
  io::writePoses(session / "pose.json", poses, io::PoseFormat::Hba);
}

TEST(SessionsCli, FarApartSessionsInTiltedFramesMeetWhereTheirPathsOverlap) {
  test::TempDir dir;
  // A 400 m loop; session 1 starts 200 m along it and drives back: the two
  // share 50 m of road, driven in opposite directions.
  test::runOk(hba() +
              " -q simulate --sessions 2 --frames 800 --session-frames 250 --session-shift 200 "
              "--session-reverse --seed 4 -o " +
              (dir / "data").string());
  tiltFrame(dir / "data" / "session-1");
  test::runOk(hba() + " -q optimize " + (dir / "data" / "session-0").string() + " " +
              (dir / "data" / "session-1").string() + " --no-render -o " + (dir / "out").string());
  for (const char* name : {"session-0", "session-1"}) {
    EXPECT_LT(test::ateInFrame(dir / "data" / name / "gt_world.txt", dir / "out" / name / "poses_tum.txt",
                               dir.path()),
              0.01)
        << name;
  }
  const nlohmann::json alignment = test::readJson(dir / "out" / "report.json").at("alignment");
  EXPECT_EQ(alignment.at("method"), "register");
  const nlohmann::json& placed = alignment.at("registered").at(0);
  EXPECT_TRUE(placed.at("found").get<bool>());
  EXPECT_GE(placed.at("agreeing").get<int>(), 2);
  ASSERT_FALSE(placed.at("pairs").empty());
  for (const nlohmann::json& pair : placed.at("pairs"))
    EXPECT_FALSE(pair.at("outcome").get<std::string>().empty());
}

// A car's path (KITTI 00, ../shared): session 1 starts 300 m further along
// it, a quarter of a kilometre away in a straight line, heading the other
// way, and drives back over part of session 0's road.
TEST(SessionsCli, SessionsAQuarterKilometreApartOnACarsPathMeet) {
  const fs::path path = test::sharedDataDir() / "trajectories" / "kitti00_gt.txt";
  if (!fs::exists(path)) GTEST_SKIP() << "no shared data: " << path;
  test::TempDir dir;
  test::runOk(hba() + " -q simulate --trajectory " + path.string() +
              " --sessions 2 --session-shift 300 --session-reverse --session-frames 300 --seed 4 -o " +
              (dir / "data").string());
  const Trajectory truth = io::readPoses(dir / "data" / "session-1" / "gt_world.txt");
  ASSERT_GT(truth.poses.front().t.norm(), 200.0);
  test::runOk(hba() + " -q optimize " + (dir / "data" / "session-0").string() + " " +
              (dir / "data" / "session-1").string() + " --no-render -o " + (dir / "out").string());
  for (const char* name : {"session-0", "session-1"}) {
    const fs::path gt = dir / "data" / name / "gt_world.txt";
    const fs::path est = dir / "out" / name / "poses_tum.txt";
    // The map is right to millimetres; its frame, anchored at session 0's
    // first pose, to a few centimetres.
    EXPECT_LT(test::evalRmse("ate", gt, est, dir.path(), "--align se3"), 0.005) << name;
    EXPECT_LT(test::ateInFrame(gt, est, dir.path()), 0.15) << name;
  }
}

TEST(SessionsCli, SessionsThatNeverMeetAreRefusedSayingWhatWasTried) {
  test::TempDir dir;
  // 75 m each, 200 m apart on a 400 m loop: no road in common.
  test::runOk(hba() +
              " -q simulate --sessions 2 --frames 800 --session-frames 150 --session-shift 200 --seed 4 -o " +
              (dir / "data").string());
  const test::CommandResult r = test::runCommand(
      hba() + " optimize " + (dir / "data" / "session-0").string() + " " +
      (dir / "data" / "session-1").string() + " --no-render -o " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("could not place this session"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("places described"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did not register"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--align FILE"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace hba
