// Format dispatch by extension, and the real hku1 sequence.
#include <gtest/gtest.h>

#include "hba/io/pcd.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_file_summary.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/io/wide_cloud.hpp"
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

// .xyz text, one entry of the format table: the points of a binary PCD
// read back alike, doubles of a UTM map to the bit, CloudCompare's
// comma-separated export with a comment, and errors naming file and line.
TEST(ScanFile, XyzTextIsOneMoreFormat) {
  test::TempDir dir;
  const PointCloud fixture = readScan(test::pcdFixture("hku1_cut_binary_compressed.pcd"));
  writeScan(dir / "hku1.xyz", fixture);
  test::expectSameCloud(fixture, readScan(dir / "hku1.xyz"));
  EXPECT_EQ(describeScanFields(dir / "hku1.xyz").fields.size(), 4u);

  WideCloud utm;
  utm.add(Vec3(500123.123456789, 4400321.987654321, 12.3456789), 7.5f);
  utm.add(Vec3(500124.000000001, 4400322.1, -0.25), 0.0f);
  writeScanWide(dir / "map.XYZ", utm);
  EXPECT_EQ(readScanWide(dir / "map.XYZ").points, utm.points);

  test::writeText(dir / "cc.xyz", "//X,Y,Z\n1.5,2.5,3.5\n\n-1,-2,-3\n");
  const WideCloud cc = readScanWide(dir / "cc.xyz");
  ASSERT_EQ(cc.size(), 2u);
  EXPECT_FALSE(cc.hasIntensity());
  EXPECT_EQ(cc.points[1], Vec3(-1, -2, -3));
  EXPECT_EQ(storedPointCount(dir / "cc.xyz"), 2u);

  // A Windows editor's byte order mark changes nothing.
  test::writeText(dir / "bom.xyz",
                  "\xEF\xBB\xBF"
                  "1.5 2.5 3.5\n");
  EXPECT_EQ(readScanWide(dir / "bom.xyz").points.at(0), Vec3(1.5, 2.5, 3.5));
  test::writeText(dir / "bad.xyz", "1 2 3\n4 5 x\n");
  test::expectErrorAbout(dir / "bad.xyz", "line 2", [&] { readScan(dir / "bad.xyz"); });
  test::writeText(dir / "ragged.xyz", "1 2 3 4\n4 5 6\n");
  test::expectErrorAbout(dir / "ragged.xyz", "line 2: 3 numbers, expected 4",
                         [&] { readScan(dir / "ragged.xyz"); });
  EXPECT_NE(scanFormatList(true).find(".xyz"), std::string::npos);  // maps may be written as text
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
