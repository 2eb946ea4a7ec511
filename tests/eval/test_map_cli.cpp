// `hba mme` and `hba map` end to end.
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "hba/eval/merged_map.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "synthetic_scans.hpp"
#include "test_support.hpp"

namespace hba::test {
namespace {

double mmeFromOutput(const CommandResult& run) {
  std::smatch m;
  const std::regex number("MME (-?[0-9.]+)");
  if (!std::regex_search(run.output, m, number)) ADD_FAILURE() << run.output;
  return m.empty() ? 0.0 : std::stod(m[1]);
}

TEST(MmeCli, Hku1ReproducesTheReferenceNumbers) {
  const auto hku1 = sharedDataDir() / "hku1";
  if (!std::filesystem::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "no " << hku1;
  const std::string base = cliPath().string() + " mme " + hku1.string();
  const CommandResult odom = runCommand(base + " --poses " + (hku1 / "odom_poses.txt").string());
  ASSERT_EQ(odom.exit_code, 0) << odom.output;
  EXPECT_NEAR(mmeFromOutput(odom), -2.97, 0.005);
  const CommandResult sc = runCommand(base + " --poses " + (hku1 / "optimized_poses.txt").string());
  ASSERT_EQ(sc.exit_code, 0) << sc.output;
  EXPECT_NEAR(mmeFromOutput(sc), -2.50, 0.005);
}

TEST(MmeCli, WrongPosesBlurTheMap) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "seq", syntheticPoses());
  Trajectory wrong;
  wrong.poses = syntheticPoses();
  wrong.poses[2].t.x() += 0.15;  // a doubled wall
  io::writePoses(tmp / "wrong.txt", wrong, io::PoseFormat::Kitti);
  const std::string base = cliPath().string() + " mme " + (tmp / "seq").string() + " --radius 0.2";
  const CommandResult good = runCommand(base);
  const CommandResult bad = runCommand(base + " --poses " + (tmp / "wrong.txt").string());
  ASSERT_EQ(good.exit_code, 0) << good.output;
  ASSERT_EQ(bad.exit_code, 0) << bad.output;
  EXPECT_GT(mmeFromOutput(bad), mmeFromOutput(good) + 0.2);

  // The same map written out and measured as a single file gives the same number.
  ASSERT_EQ(runCommand(cliPath().string() + " map " + (tmp / "seq").string() + " -o " +
                       (tmp / "map.pcd").string() + " --voxel 0.1")
                .exit_code,
            0);
  const CommandResult from_file =
      runCommand(cliPath().string() + " mme --map " + (tmp / "map.pcd").string() + " --voxel 0 --radius 0.2");
  EXPECT_NEAR(mmeFromOutput(from_file), mmeFromOutput(good), 1e-4) << from_file.output;
}

TEST(MapCli, PclReadsTheMapWithTheSamePointCount) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "seq", syntheticPoses());
  const CommandResult run = runCommand(cliPath().string() + " map " + (tmp / "seq").string() + " -o " +
                                       (tmp / "map.pcd").string() + " --voxel 0.1 --color height");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const PointCloud map = io::readPcd(tmp / "map.pcd");
  ASSERT_GT(map.size(), 1000u);
  ASSERT_TRUE(map.hasIntensity());
  for (std::size_t i = 0; i < map.size(); i += 97) EXPECT_FLOAT_EQ(map.intensity[i], map.points[i].z());

  if (std::system("command -v pcl_pcd2ply > /dev/null 2>&1") != 0) GTEST_SKIP() << "pcl-tools absent";
  const CommandResult pcl =
      runCommand("pcl_pcd2ply -format 0 " + (tmp / "map.pcd").string() + " " + (tmp / "pcl.ply").string());
  ASSERT_EQ(pcl.exit_code, 0) << pcl.output;
  const std::string header = readText(tmp / "pcl.ply").substr(0, 400);
  EXPECT_NE(header.find("element vertex " + std::to_string(map.size()) + "\n"), std::string::npos) << header;
  EXPECT_EQ(io::readPly(tmp / "pcl.ply").size(), map.size());
}

// `hba map` merges the dataset's scans as buildMergedMap merges the same
// scans held in memory: the same file, byte for byte.
TEST(MapCli, SameMapAsTheScansMergedFromMemory) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "seq", syntheticPoses());
  const CommandResult run = runCommand(cliPath().string() + " map " + (tmp / "seq").string() + " -o " +
                                       (tmp / "map.pcd").string() + " --voxel 0.1 --color scan");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<Pose> poses =
      io::readPoses(tmp / "seq" / "odom_poses.txt").poses;  // as the tool reads them
  eval::MapSettings settings;
  settings.voxel = 0.1;
  settings.color = eval::MapColor::Scan;
  const io::MemoryScanSource scans(syntheticScans(syntheticPoses()));
  io::writePcd(tmp / "memory.pcd", eval::buildMergedMap(scans, poses, settings));
  EXPECT_EQ(readText(tmp / "map.pcd"), readText(tmp / "memory.pcd"));
}

TEST(MapCli, WritesPlyAndRefusesToWriteIntoTheInput) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "seq", syntheticPoses());
  const std::string base = cliPath().string() + " map " + (tmp / "seq").string() + " -o ";
  ASSERT_EQ(runCommand(base + (tmp / "map.ply").string()).exit_code, 0);
  EXPECT_GT(io::readPly(tmp / "map.ply").size(), 1000u);
  const CommandResult into_scans = runCommand(base + (tmp / "seq" / "Scans" / "map.pcd").string());
  EXPECT_NE(into_scans.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(tmp / "seq" / "Scans" / "map.pcd"));
  EXPECT_NE(runCommand(base + (tmp / "map.xyz").string()).exit_code, 0);
}

}  // namespace
}  // namespace hba::test
