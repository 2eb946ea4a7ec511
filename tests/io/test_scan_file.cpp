// Format dispatch by extension, and the real hku1 sequence.
#include <gtest/gtest.h>

#include "hba/io/pcd.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

TEST(ScanFile, FormatFollowsTheExtensionInAnyCase) {
  EXPECT_STREQ(scanFormatOf("a/000001.pcd").name, "PCD");
  EXPECT_STREQ(scanFormatOf("a/000001.PCD").name, "PCD");
  EXPECT_STREQ(scanFormatOf("velodyne/000001.bin").name, "KITTI .bin");
  EXPECT_STREQ(scanFormatOf("cloud.Ply").name, "PLY");
  EXPECT_STREQ(scanFormatOf("survey/strip.LAS").name, "LAS");
  EXPECT_TRUE(isScanFile("x.pcd"));
  EXPECT_FALSE(isScanFile("pose.json"));
  EXPECT_FALSE(isScanFile("pcd"));
  test::expectErrorAbout("scan.laz", "unknown scan format '.laz'", [] { scanFormatOf("scan.laz"); });
}

// Every message that lists the formats takes the list from the table.
TEST(ScanFile, ErrorsListTheFormatsOfTheTable) {
  const std::string list = scanFormatList();
  for (const ScanFormat& format : scanFormats()) EXPECT_NE(list.find(format.extension), std::string::npos);
  test::expectErrorAbout("scan.laz", list, [] { readScan("scan.laz"); });
  EXPECT_EQ(scanFormatList(true).find(".bin"), std::string::npos);  // float32 only: no maps
}

TEST(ScanFile, WritesAndReadsEveryFormatByExtension) {
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(50, true);
  for (const char* name : {"s.pcd", "s.bin", "s.ply"}) {
    SCOPED_TRACE(name);
    writeScan(dir / name, cloud);
    test::expectSameCloud(cloud, readScan(dir / name));
  }
  test::expectSameCloud(readScan(dir / "s.pcd"), readScan(dir / "s.ply"));
}

TEST(ScanFile, ReadsTheFixturesOfEveryFormatAlike) {
  const PointCloud pcd = readScan(test::pcdFixture("hku1_cut_binary_compressed.pcd"));
  test::expectSameCloud(pcd, readScan(test::binFixture("hku1_cut.bin")));
  test::expectSameCloud(pcd, readScan(test::plyFixture("hku1_cut_binary.ply")));
}

// All 314 Livox scans of the hku1 sequence read, with intensity, and agree
// with their headers (they hold no NaN points).
TEST(ScanFile, EveryHku1ScanReads) {
  const fs::path scans = test::sharedDataDir() / "hku1" / "Scans";
  if (!fs::is_directory(scans)) GTEST_SKIP() << "no " << scans;
  std::size_t files = 0;
  std::size_t total_points = 0;
  for (const auto& entry : fs::directory_iterator(scans)) {
    if (!isScanFile(entry.path())) continue;
    const PointCloud cloud = readScan(entry.path());
    const PcdHeader header = readPcdHeader(entry.path());
    ASSERT_EQ(cloud.size(), header.points) << entry.path();
    ASSERT_TRUE(cloud.hasIntensity()) << entry.path();
    ASSERT_GT(cloud.size(), 0u) << entry.path();
    ++files;
    total_points += cloud.size();
  }
  EXPECT_EQ(files, 314u);
  RecordProperty("points", static_cast<int>(total_points));
}

}  // namespace
}  // namespace hba::io
