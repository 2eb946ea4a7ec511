// Writing a simulated sequence: layout, contents, determinism across thread
// counts, and never damaging an existing folder.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>

#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/simulation.hpp"
#include "test_support.hpp"

namespace hba::sim {
namespace {
namespace fs = std::filesystem;

// Small and quick: 12 frames of a coarse 16-channel sensor.
Simulation tinySimulation(std::uint64_t seed = 1) {
  SimulationConfig config;
  config.seed = seed;
  config.trajectory.frames = 12;
  config.sensor.columns = 360;
  return prepareSimulation(config);
}

TEST(SimOutput, WritesAnHbaFolderWithGroundTruth) {
  hba::test::TempDir dir;
  const Simulation simulation = tinySimulation();
  writeSimulation(simulation, dir / "seq", WriteOptions{});

  const fs::path seq = dir / "seq";
  ASSERT_TRUE(fs::is_regular_file(seq / "pcd" / "000000.pcd"));
  ASSERT_TRUE(fs::is_regular_file(seq / "pcd" / "000011.pcd"));
  EXPECT_FALSE(fs::exists(seq / "pcd" / "000012.pcd"));
  const PointCloud cloud = io::readPcd(seq / "pcd" / "000005.pcd");
  EXPECT_GT(cloud.size(), 1000u);
  EXPECT_TRUE(cloud.hasIntensity());
  const io::PcdHeader header = io::readPcdHeader(seq / "pcd" / "000005.pcd");
  EXPECT_EQ(header.encoding, io::PcdEncoding::Binary);

  const Trajectory truth = io::readPoses(seq / "gt.txt", io::PoseFormat::Tum);
  const Trajectory initial = io::readPoses(seq / "pose.json", io::PoseFormat::Hba);
  ASSERT_EQ(truth.size(), 12u);
  ASSERT_EQ(initial.size(), 12u);
  EXPECT_NEAR(truth.stamps[3], 0.3, 1e-12);
  EXPECT_LT((truth.poses[7].t - simulation.truth.poses[7].t).norm(), 1e-9);
  EXPECT_LT((initial.poses[7].t - simulation.initial[7].t).norm(), 1e-9);

  const std::string yaml = hba::test::readText(seq / "sim.yaml");
  EXPECT_NE(yaml.find("seed: 1"), std::string::npos);
  EXPECT_NE(yaml.find("version:"), std::string::npos);
  EXPECT_NE(yaml.find("range_noise_m: 0.02"), std::string::npos);
  // No staging leftovers beside the output.
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename(), "seq");
  }
}

// --sweep: the scans carry each point's time in the frame's interval, and
// the same frames without it have none; a voxel's centroid has no time.
TEST(SimOutput, RawSweepsCarryTheirPointTimes) {
  hba::test::TempDir dir;
  SimulationConfig config = tinySimulation().config;
  config.sweep = true;
  writeSimulation(prepareSimulation(config), dir / "raw", WriteOptions{});
  const PointCloud cloud = io::readPcd(dir / "raw" / "pcd" / "000005.pcd");
  ASSERT_EQ(cloud.time.size(), cloud.size());
  EXPECT_GE(*std::min_element(cloud.time.begin(), cloud.time.end()), 0.0);
  EXPECT_GT(*std::max_element(cloud.time.begin(), cloud.time.end()), 0.09);
  EXPECT_LT(*std::max_element(cloud.time.begin(), cloud.time.end()), 0.1);
  EXPECT_NE(hba::test::readText(dir / "raw" / "sim.yaml").find("raw_sweeps: true"), std::string::npos);
  EXPECT_FALSE(simulateFrame(tinySimulation(), 5).hasTime());
  config.downsample_voxel = 0.2;
  EXPECT_THROW(prepareSimulation(config), Error);
}

TEST(SimOutput, SameSeedSameBytesWithOneOrTwoThreads) {
  hba::test::TempDir dir;
  const Simulation simulation = tinySimulation(5);
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    writeSimulation(simulation, dir / "one", WriteOptions{});
  }
  {
    const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    writeSimulation(tinySimulation(5), dir / "two", WriteOptions{});
  }
  const auto one = hba::test::fileContents(dir / "one");
  const auto two = hba::test::fileContents(dir / "two");
  ASSERT_EQ(one.size(), 16u);  // 12 scans + pose.json + gt.txt + times.txt + sim.yaml
  EXPECT_TRUE(one == two) << "outputs differ between 1 and 2 threads";

  writeSimulation(tinySimulation(6), dir / "other", WriteOptions{});
  EXPECT_NE(hba::test::fileContents(dir / "other").at("pcd/000003.pcd"), one.at("pcd/000003.pcd"));
}

Simulation tinyLoopClosedSimulation() {
  SimulationConfig config = tinySimulation().config;
  config.drift.loop_closed = true;
  return prepareSimulation(config);
}

TEST(SimOutput, ScansDoNotDependOnTheDriftModel) {
  hba::test::TempDir dir;
  writeSimulation(tinySimulation(), dir / "drift", WriteOptions{});
  writeSimulation(tinyLoopClosedSimulation(), dir / "loop", WriteOptions{});
  const auto drift = hba::test::fileContents(dir / "drift");
  const auto loop = hba::test::fileContents(dir / "loop");
  ASSERT_EQ(drift.size(), loop.size());
  EXPECT_NE(drift.at("pose.json"), loop.at("pose.json"));
  for (const auto& [name, bytes] : drift) {
    if (name.rfind("pcd/", 0) == 0) {
      EXPECT_EQ(bytes, loop.at(name)) << name;
    }
  }
}

TEST(SimOutput, PosesOnlyWritesTheSamePoseFilesAndNoScans) {
  hba::test::TempDir dir;
  writeSimulation(tinyLoopClosedSimulation(), dir / "full", WriteOptions{});
  WriteOptions poses_only;
  poses_only.poses_only = true;
  writeSimulation(tinyLoopClosedSimulation(), dir / "poses", poses_only);

  const auto full = hba::test::fileContents(dir / "full");
  const auto poses = hba::test::fileContents(dir / "poses");
  EXPECT_FALSE(fs::exists(dir / "poses" / "pcd"));
  ASSERT_EQ(poses.size(), 4u);
  for (const char* name : {"pose.json", "gt.txt", "times.txt", "sim.yaml"}) {
    EXPECT_EQ(poses.at(name), full.at(name)) << name;
  }
}

TEST(SimOutput, RefusesANonEmptyFolderUnlessForced) {
  hba::test::TempDir dir;
  fs::create_directory(dir / "data");
  hba::test::writeText(dir / "data" / "precious.txt", "keep me");
  const Simulation simulation = tinySimulation();
  EXPECT_THROW(writeSimulation(simulation, dir / "data", WriteOptions{}), Error);
  EXPECT_EQ(hba::test::readText(dir / "data" / "precious.txt"), "keep me");
  EXPECT_FALSE(fs::exists(dir / "data" / "pose.json"));

  // --force replaces only what hba wrote: a folder of the user's stays.
  WriteOptions forced;
  forced.force = true;
  EXPECT_THROW(writeSimulation(simulation, dir / "data", forced), Error);
  EXPECT_EQ(hba::test::readText(dir / "data" / "precious.txt"), "keep me");
  // An earlier output (its marker) is replaced whole.
  hba::test::writeText(dir / "data" / ".hba-output", "");
  writeSimulation(simulation, dir / "data", forced);
  EXPECT_FALSE(fs::exists(dir / "data" / "precious.txt"));
  EXPECT_TRUE(fs::exists(dir / "data" / "pose.json"));
}

TEST(SimOutput, AcceptsAnEmptyExistingFolder) {
  hba::test::TempDir dir;
  fs::create_directory(dir / "empty");
  writeSimulation(tinySimulation(), dir / "empty", WriteOptions{});
  EXPECT_TRUE(fs::exists(dir / "empty" / "gt.txt"));
}

TEST(SimOutput, FailureLeavesNothingThatLooksComplete) {
  hba::test::TempDir dir;
  Simulation simulation = tinySimulation();
  simulation.truth.poses.pop_back();  // frame 11 now has no pose: scanning it throws
  EXPECT_ANY_THROW(writeSimulation(simulation, dir / "broken", WriteOptions{}));
  EXPECT_FALSE(fs::exists(dir / "broken"));
  EXPECT_TRUE(fs::is_empty(dir.path())) << "the staging folder was removed";
}

TEST(SimOutput, ReportsProgress) {
  hba::test::TempDir dir;
  std::vector<std::size_t> reports;
  WriteOptions options;
  options.progress_every = 5;
  options.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, 12u);
    reports.push_back(done);
  };
  writeSimulation(tinySimulation(), dir / "seq", options);
  EXPECT_EQ(reports, (std::vector<std::size_t>{5, 10, 12}));
}

TEST(SimOutput, ScanNamesArePaddedToSixDigitsOrMore) {
  EXPECT_EQ(scanFileName(7, 300), "000007.pcd");
  EXPECT_EQ(scanFileName(999999, 1000000), "999999.pcd");
  EXPECT_EQ(scanFileName(5, 1000001), "0000005.pcd");
}

}  // namespace
}  // namespace hba::sim
