// `hba mme` and `hba map` end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <set>

#include "hba/eval/merged_map.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"
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
  // A format the table does not hold, and one that cannot keep a map's
  // coordinates (float32 .bin), are refused naming the formats that can.
  const CommandResult unknown = runCommand(base + (tmp / "map.e57").string() + " 2>&1");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find(".pcd, .ply, .las or .xyz"), std::string::npos) << unknown.output;
  EXPECT_NE(runCommand(base + (tmp / "map.bin").string()).exit_code, 0);
  // .xyz text keeps them: the same map as the PLY's.
  ASSERT_EQ(runCommand(base + (tmp / "map.xyz").string()).exit_code, 0);
  EXPECT_EQ(io::readScan(tmp / "map.xyz").size(), io::readPly(tmp / "map.ply").size());
}

// A LAS map carries the intensity --color chose and, in every point's point
// source ID, the first scan's index, whatever --color says.
TEST(MapCli, WritesLasWithIntensityAndScanIndex) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "seq", syntheticPoses());
  const std::string base = cliPath().string() + " map " + (tmp / "seq").string() + " --voxel 0.1 -o ";
  ASSERT_EQ(runCommand(base + (tmp / "map.las").string()).exit_code, 0);
  ASSERT_EQ(runCommand(base + (tmp / "map.pcd").string()).exit_code, 0);
  ASSERT_EQ(runCommand(base + (tmp / "scans.pcd").string() + " --color scan").exit_code, 0);
  const PointCloud las = io::readLas(tmp / "map.las");
  const PointCloud pcd = io::readPcd(tmp / "map.pcd");
  const PointCloud scans = io::readPcd(tmp / "scans.pcd");
  ASSERT_GT(pcd.size(), 1000u);
  ASSERT_EQ(las.size(), pcd.size());
  ASSERT_TRUE(pcd.hasIntensity());
  const std::string bytes = readText(tmp / "map.las");
  const std::size_t first_record = 375, record_length = 30, source_id = 20;
  std::set<std::uint16_t> seen;
  for (std::size_t i = 0; i < las.size(); ++i) {
    ASSERT_LE((las.world(i) - pcd.world(i)).cwiseAbs().maxCoeff(), 0.0005 + 1e-6) << "point " << i;
    ASSERT_EQ(las.intensity[i], std::round(pcd.intensity[i])) << "point " << i;
    std::uint16_t scan = 0;
    std::memcpy(&scan, &bytes[first_record + i * record_length + source_id], sizeof(scan));
    ASSERT_EQ(scan, scans.intensity[i]) << "point " << i;
    seen.insert(scan);
  }
  EXPECT_EQ(seen.size(), syntheticPoses().size());  // every scan contributed
}

// A dataset whose scans are .las files reads like one of .pcd files.
TEST(MapCli, ADatasetOfLasScansGivesTheSameMap) {
  TempDir tmp;
  writeSyntheticDataset(tmp / "pcd", syntheticPoses());
  std::filesystem::create_directories(tmp / "las" / "Scans");
  const std::vector<PointCloud> clouds = syntheticScans(syntheticPoses());
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    io::writeLas(tmp / "las" / "Scans" / (std::to_string(i) + ".las"), clouds[i]);
  }
  std::filesystem::copy_file(tmp / "pcd" / "odom_poses.txt", tmp / "las" / "odom_poses.txt");
  const CommandResult info = runCommand(cliPath().string() + " info " + (tmp / "las").string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find(".las"), std::string::npos) << info.output;
  const std::string map = " map --voxel 0 -o ";
  ASSERT_EQ(runCommand(cliPath().string() + map + (tmp / "las.pcd").string() + " " + (tmp / "las").string())
                .exit_code,
            0);
  ASSERT_EQ(runCommand(cliPath().string() + map + (tmp / "pcd.pcd").string() + " " + (tmp / "pcd").string())
                .exit_code,
            0);
  const PointCloud from_las = io::readPcd(tmp / "las.pcd");
  const PointCloud from_pcd = io::readPcd(tmp / "pcd.pcd");
  ASSERT_EQ(from_las.size(), from_pcd.size());
  for (std::size_t i = 0; i < from_las.size(); i += 13) {
    ASSERT_LE((from_las.world(i) - from_pcd.world(i)).cwiseAbs().maxCoeff(), 0.001) << "point " << i;
  }
}

}  // namespace
}  // namespace hba::test
