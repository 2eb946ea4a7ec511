// What `hba info` reports of a scan file: its point count without reading
// the points where the format allows, its fields and their encoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hba/io/kitti_bin.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_file_summary.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

using Fields = std::vector<std::string>;

TEST(ScanFileSummary, PointCountsOfEveryFormat) {
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(37, true);
  for (const char* name : {"a.pcd", "a.bin", "a.ply", "a.las"}) {
    writeScan(dir / name, cloud);
    EXPECT_EQ(storedPointCount(dir / name), 37u) << name;
  }
}

TEST(ScanFileSummary, FieldsAndEncodingOfEveryFormat) {
  const ScanFileFields pcd = describeScanFields(test::pcdFixture("hku1_cut_binary_compressed.pcd"));
  EXPECT_EQ(pcd.fields, (Fields{"x", "y", "z", "intensity"}));
  EXPECT_EQ(pcd.encoding, "PCD binary_compressed");
  EXPECT_EQ(describeScanFields(test::pcdFixture("hku1_cut_ascii.pcd")).encoding, "PCD ascii");
  const ScanFileFields fpfh = describeScanFields(test::pcdFixture("fpfh_binary.pcd"));
  EXPECT_NE(std::find(fpfh.fields.begin(), fpfh.fields.end(), "fpfh[33]"), fpfh.fields.end());
  EXPECT_EQ(fpfh.encoding, "PCD binary");
  const ScanFileFields bin = describeScanFields(test::binFixture("hku1_cut.bin"));
  EXPECT_EQ(bin.fields, (Fields{"x", "y", "z", "intensity"}));
  EXPECT_EQ(bin.encoding, "KITTI float32");
  const ScanFileFields ply = describeScanFields(test::plyFixture("hku1_cut_binary.ply"));
  EXPECT_EQ(ply.fields, (Fields{"x", "y", "z", "intensity"}));
  EXPECT_EQ(ply.encoding, "PLY");
  test::TempDir dir;
  writeScan(dir / "a.las", test::makeCloud(5, true));
  const ScanFileFields las = describeScanFields(dir / "a.las");
  EXPECT_EQ(las.fields, (Fields{"x", "y", "z", "intensity"}));
  EXPECT_EQ(las.encoding, "LAS 1.4 point format 6");
}

TEST(ScanFileSummary, BadFilesAreErrorsNamingThem) {
  test::TempDir dir;
  test::writeText(dir / "odd.bin", std::string(20, '\0'));
  test::expectErrorAbout(dir / "odd.bin", "not a multiple of 16", [&] { storedPointCount(dir / "odd.bin"); });
  test::writeText(dir / "scan.e57", "");
  test::expectErrorAbout(dir / "scan.e57", "unknown scan format",
                         [&] { describeScanFields(dir / "scan.e57"); });
}

}  // namespace
}  // namespace hba::io
