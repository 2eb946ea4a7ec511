// MCAP files written by npm's @mcap/core with CDR messages from
// @foxglove/rosmsg2-serialization (not by hba) read back: zstd and
// uncompressed chunks, bad files, and hku1 end to end.
#include <gtest/gtest.h>

#include "bag_fixture.hpp"
#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/rec/recording.hpp"

namespace hba::rec {
namespace {
namespace fs = std::filesystem;

class McapCompression : public ::testing::TestWithParam<const char*> {};

TEST_P(McapCompression, ReadsWhatMcapCoreWrote) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_OR_SKIP(dir / "folder", dir / "run.mcap", GetParam());
  const Recording recording = Recording::open(dir / "run.mcap");
  EXPECT_EQ(recording.format(), "MCAP");
  EXPECT_EQ(io::Dataset::open(dir / "run.mcap").layout(), "ros2-bag");
  EXPECT_EQ(recording.cloudTopic(), "/cloud_registered_body");
  EXPECT_EQ(recording.poseTopic(), "/Odometry");
  EXPECT_EQ(recording.cloudFrame(), "body");
  ASSERT_EQ(recording.size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_NEAR(recording.trajectory().stamps[k], folder.stamps[k], 1e-6);
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(test::angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
    const PointCloud scan = recording.loadScan(k);
    ASSERT_EQ(scan.size(), folder.scans[k].size());
    EXPECT_EQ(scan.points, folder.scans[k].points);
    EXPECT_EQ(scan.intensity, folder.scans[k].intensity);
  }
}

INSTANTIATE_TEST_SUITE_P(Chunks, McapCompression, ::testing::Values("zstd", "none"));

std::string openError(const fs::path& path) {
  try {
    const Recording recording = Recording::open(path);
    for (std::size_t i = 0; i < recording.size(); ++i) recording.loadScan(i);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(McapErrors, TruncatedOrUnknownCompression) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 6);
  WRITE_MCAP_OR_SKIP(dir / "folder", dir / "run.mcap", "zstd");
  const std::string bytes = test::readText(dir / "run.mcap");
  test::writeText(dir / "cut.mcap", bytes.substr(0, bytes.size() / 2));
  const std::string cut = openError(dir / "cut.mcap");
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
  test::writeText(dir / "lzma.mcap", test::renamedChunkCompression(bytes, "zstd", "lzma"));
  const std::string lzma = openError(dir / "lzma.mcap");
  EXPECT_NE(lzma.find("unknown chunk compression 'lzma'"), std::string::npos) << lzma;
}

TEST(McapReal, Hku1McapGivesTheFolderRunsPoses) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "../shared/data/hku1 is absent";
  test::TempDir dir;
  WRITE_MCAP_OR_SKIP(hku1, dir / "hku1.mcap", "zstd");
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + (dir / "hku1.mcap").string() + " -o " +
              (dir / "from_mcap").string() + " --no-render");
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + hku1.string() + " -o " +
              (dir / "from_folder").string() + " --no-render");
  const double rmse = test::evalRmse("ate", dir / "from_folder" / "poses_kitti.txt",
                                     dir / "from_mcap" / "poses_kitti.txt", dir.path(), "--align none");
  EXPECT_LT(rmse, 1e-3);
}

}  // namespace
}  // namespace hba::rec
