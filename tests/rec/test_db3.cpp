// ROS 2 sqlite3 bags (rosbag2 folders of .db3 files, as Humble records
// them): messages serialized by npm's @foxglove/rosmsg2-serialization and
// stored by Python's sqlite3, read back by hba, the files untouched.
#include <gtest/gtest.h>

#include "bag_fixture.hpp"
#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/rec/recording.hpp"

namespace hba::rec {
namespace {
namespace fs = std::filesystem;

void expectFolderRead(const Recording& recording, const test::ScanFolder& folder) {
  ASSERT_EQ(recording.size(), folder.poses.size());
  EXPECT_EQ(recording.cloudTopic(), "/cloud_registered_body");
  EXPECT_EQ(recording.poseTopic(), "/Odometry");
  for (std::size_t k = 0; k < recording.size(); ++k) {
    EXPECT_NEAR(recording.trajectory().stamps[k], folder.stamps[k], 1e-6);
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(test::angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
    const PointCloud scan = recording.loadScan(k);
    EXPECT_EQ(scan.points, folder.scans[k].points);
    EXPECT_EQ(scan.intensity, folder.scans[k].intensity);
  }
}

TEST(Db3, ReadsARosbag2FolderAndItsFileAlone) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 10);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 1);
  const std::string bytes = test::readText(dir / "bag" / "run_0.db3");
  const Recording from_folder = Recording::open(dir / "bag");
  EXPECT_EQ(from_folder.format(), "ROS 2 sqlite3 bag");
  expectFolderRead(from_folder, folder);
  expectFolderRead(Recording::open(dir / "bag" / "run_0.db3"), folder);
  EXPECT_EQ(io::Dataset::open(dir / "bag").size(), 10u);
  // Opened immutable: no journal beside it, not a byte changed.
  EXPECT_EQ(test::fileContents(dir / "bag").size(), 2u);
  EXPECT_EQ(test::readText(dir / "bag" / "run_0.db3"), bytes);
}

TEST(Db3, ASplitRecordingReadsAsOne) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 10);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 3);
  const Recording recording = Recording::open(dir / "bag");
  EXPECT_NE(recording.format().find("rosbag2 folder"), std::string::npos) << recording.format();
  expectFolderRead(recording, folder);
}

TEST(Db3, AMissingStorageFileIsNamed) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 4);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 2);
  fs::remove(dir / "bag" / "run_1.db3");
  try {
    Recording::open(dir / "bag");
    FAIL() << "opened a folder without its second file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("run_1.db3: no such file"), std::string::npos) << e.what();
  }
}

TEST(Db3Real, Hku1SplitDb3GivesTheFolderRunsPoses) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "../shared/data/hku1 is absent";
  test::TempDir dir;
  WRITE_DB3_OR_SKIP(hku1, dir / "bag", 2);
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + (dir / "bag").string() + " -o " +
              (dir / "from_db3").string() + " --no-render");
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + hku1.string() + " -o " +
              (dir / "from_folder").string() + " --no-render");
  EXPECT_LT(test::evalRmse("ate", dir / "from_folder" / "poses_kitti.txt",
                           dir / "from_db3" / "poses_kitti.txt", dir.path(), "--align none"),
            1e-3);
}

}  // namespace
}  // namespace hba::rec
