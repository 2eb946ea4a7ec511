// Writing several sessions: one complete dataset folder each, files that
// agree with each other, the same bytes whatever the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <fstream>
#include <sstream>

#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/sessions.hpp"
#include "session_test_support.hpp"
#include "test_support.hpp"

namespace hba::sim {
namespace {
namespace fs = std::filesystem;
using test::posesNear;

// Small and quick: 12 frames of a coarse 16-channel sensor, two sessions 2 m apart.
SessionSet tinySessions(bool reverse = false) {
  SimulationConfig config;
  config.seed = 2;
  config.trajectory.frames = 12;
  config.sensor.columns = 360;
  SessionsConfig sessions;
  sessions.count = 2;
  sessions.shift = 2.0;
  sessions.reverse = reverse;
  return prepareSessions(config, sessions);
}

Pose readSessionFrame(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // the comment naming the fields
  EXPECT_EQ(line.rfind("# world_from_session", 0), 0u) << line;
  double tx, ty, tz, qx, qy, qz, qw;
  in >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
  EXPECT_TRUE(in) << path;
  return Pose(Quat(qw, qx, qy, qz), Vec3(tx, ty, tz));
}

TEST(SimSessionsOutput, WritesOneCompleteDatasetPerSession) {
  hba::test::TempDir dir;
  const SessionSet set = tinySessions();
  writeSessions(set, dir / "out", WriteOptions{});
  for (const char* session : {"session-0", "session-1"}) {
    const fs::path folder = dir / "out" / session;
    for (const char* name : {"pose.json", "gt.txt", "gt_world.txt", "session_frame.txt", "times.txt",
                             "sim.yaml", "pcd/000000.pcd", "pcd/000011.pcd"}) {
      EXPECT_TRUE(fs::is_regular_file(folder / name)) << folder / name;
    }
    const Trajectory gt = io::readPoses(folder / "gt.txt", io::PoseFormat::Tum);
    const Trajectory gt_world = io::readPoses(folder / "gt_world.txt", io::PoseFormat::Tum);
    const Trajectory initial = io::readPoses(folder / "pose.json", io::PoseFormat::Hba);
    const Pose frame = readSessionFrame(folder / "session_frame.txt");
    ASSERT_EQ(gt.size(), 12u);
    ASSERT_EQ(gt_world.size(), 12u);
    ASSERT_EQ(initial.size(), 12u);
    // An odometry's start: pose 0 of pose.json and gt.txt is the identity.
    EXPECT_TRUE(posesNear(initial.poses[0], Pose::identity(), 0.0)) << session;
    EXPECT_TRUE(posesNear(gt.poses[0], Pose::identity(), 0.0)) << session;
    for (std::size_t k = 0; k < gt.size(); ++k) {
      EXPECT_EQ(gt.stamps[k], gt_world.stamps[k]);
      EXPECT_TRUE(posesNear(gt_world.poses[k], frame * gt.poses[k], 1e-9)) << session << " " << k;
    }
    const std::string yaml = hba::test::readText(folder / "sim.yaml");
    EXPECT_NE(yaml.find("session:"), std::string::npos) << yaml;
    EXPECT_NE(yaml.find("gt_world.txt"), std::string::npos) << yaml;
  }
  // Session 0's frame is the common frame.
  EXPECT_TRUE(
      posesNear(readSessionFrame(dir / "out" / "session-0" / "session_frame.txt"), Pose::identity(), 0.0));
  // No staging folder or lock left behind.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST(SimSessionsOutput, OneAndTwoThreadsWriteTheSameBytes) {
  hba::test::TempDir dir;
  for (bool reverse : {false, true}) {
    const SessionSet set = tinySessions(reverse);
    const std::string suffix = reverse ? "-reverse" : "";
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      writeSessions(set, dir / ("one" + suffix), WriteOptions{});
    }
    {
      tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
      writeSessions(set, dir / ("two" + suffix), WriteOptions{});
    }
    const auto one = hba::test::fileContents(dir / ("one" + suffix));
    EXPECT_EQ(one.size(), 2u * (12u + 6u));
    EXPECT_TRUE(one == hba::test::fileContents(dir / ("two" + suffix)));
  }
  // Preparing again gives the same bytes too (nothing depends on addresses or time).
  writeSessions(tinySessions(), dir / "again", WriteOptions{});
  EXPECT_TRUE(hba::test::fileContents(dir / "one") == hba::test::fileContents(dir / "again"));
}

TEST(SimSessionsOutput, PosesOnlyWritesTheSamePoseFilesWithoutScans) {
  hba::test::TempDir dir;
  const SessionSet set = tinySessions();
  writeSessions(set, dir / "full", WriteOptions{});
  WriteOptions poses_only;
  poses_only.poses_only = true;
  writeSessions(set, dir / "poses", poses_only);
  const auto full = hba::test::fileContents(dir / "full");
  const auto poses = hba::test::fileContents(dir / "poses");
  ASSERT_EQ(poses.size(), 2u * 6u);
  for (const auto& [name, contents] : poses) EXPECT_EQ(contents, full.at(name)) << name;
}

TEST(SimSessionsOutput, TrajectoryFileSessionsStartAtTheShiftAndStopAtTheFileEnds) {
  hba::test::TempDir dir;
  // A straight 30 m drive along x, one pose every metre.
  Trajectory drive;
  for (int k = 0; k <= 30; ++k) {
    drive.poses.emplace_back(Quat::Identity(), Vec3(k, 0.0, 0.0));
    drive.stamps.push_back(0.1 * k);
  }
  io::writePoses(dir / "drive.txt", drive, io::PoseFormat::Tum);
  SimulationConfig config;
  config.trajectory.file = dir / "drive.txt";
  config.trajectory.frames = 20;
  SessionsConfig sessions;
  sessions.count = 3;
  sessions.shift = 7.0;
  sessions.reverse = true;
  const SessionSet set = prepareSessions(config, sessions);
  ASSERT_EQ(set.list.size(), 3u);
  EXPECT_EQ(set.list[0].truth.size(), 20u);
  // Session 1 drives back from x = 7 to the file's first pose: 8 frames.
  EXPECT_EQ(set.list[1].truth.size(), 8u);
  EXPECT_NEAR(set.list[1].truth_simulator.poses[0].t.x(), 7.0, 1e-9);
  EXPECT_NEAR(set.list[1].truth_simulator.poses.back().t.x(), 0.0, 1e-9);
  EXPECT_LT(set.list[1].truth_simulator.poses[0].R().col(0).x(), -0.99);  // facing back along -x
  // Session 2 drives on from x = 14 to the file's last pose: 17 frames.
  EXPECT_EQ(set.list[2].truth.size(), 17u);
  EXPECT_NEAR(set.list[2].truth_simulator.poses[0].t.x(), 14.0, 1e-9);
  // A start beyond the file's end is an error that names the file.
  sessions.shift = 40.0;
  try {
    prepareSessions(config, sessions);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("drive.txt"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hba::sim
