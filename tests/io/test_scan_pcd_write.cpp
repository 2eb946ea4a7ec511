// writePcd: exact round trips in every encoding, atomic replacement.
#include <gtest/gtest.h>

#include "hba/io/pcd.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

const PcdEncoding kEncodings[] = {PcdEncoding::Ascii, PcdEncoding::Binary, PcdEncoding::BinaryCompressed};

TEST(PcdWrite, RoundTripsFloatsExactlyInEveryEncoding) {
  test::TempDir dir;
  for (const bool with_intensity : {true, false}) {
    const PointCloud cloud = test::makeCloud(1000, with_intensity);
    for (const PcdEncoding encoding : kEncodings) {
      SCOPED_TRACE(static_cast<int>(encoding));
      writePcd(dir / "out.pcd", cloud, encoding);
      test::expectSameCloud(cloud, readPcd(dir / "out.pcd"));
      EXPECT_EQ(readPcdHeader(dir / "out.pcd").encoding, encoding);
    }
  }
}

TEST(PcdWrite, RoundTripsExtremeFloats) {
  PointCloud cloud;
  cloud.add(Vec3f(std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min(), -0.0f),
            1e-38f);
  cloud.add(Vec3f(std::numeric_limits<float>::lowest(), 1e-45f, 16777217.0f), -3.4e38f);
  test::TempDir dir;
  for (const PcdEncoding encoding : kEncodings) {
    writePcd(dir / "out.pcd", cloud, encoding);
    test::expectSameCloud(cloud, readPcd(dir / "out.pcd"));
  }
}

TEST(PcdWrite, HeaderDeclaresFieldsAndCounts) {
  test::TempDir dir;
  writePcd(dir / "out.pcd", test::makeCloud(5, true));
  const PcdHeader header = readPcdHeader(dir / "out.pcd");
  ASSERT_EQ(header.fields.size(), 4u);
  EXPECT_EQ(header.fields[3].name, "intensity");
  EXPECT_EQ(header.points, 5u);
  EXPECT_EQ(header.encoding, PcdEncoding::Binary);
  writePcd(dir / "out.pcd", test::makeCloud(5, false));
  EXPECT_EQ(readPcdHeader(dir / "out.pcd").fields.size(), 3u);
}

TEST(PcdWrite, EmptyCloudRoundTrips) {
  test::TempDir dir;
  for (const PcdEncoding encoding : kEncodings) {
    writePcd(dir / "empty.pcd", PointCloud(), encoding);
    EXPECT_TRUE(readPcd(dir / "empty.pcd").empty());
  }
}

TEST(PcdWrite, ReplacesAnExistingFileAndLeavesNoTemporary) {
  test::TempDir dir;
  writePcd(dir / "out.pcd", test::makeCloud(10, true));
  writePcd(dir / "out.pcd", test::makeCloud(3, false), PcdEncoding::BinaryCompressed);
  EXPECT_EQ(readPcd(dir / "out.pcd").size(), 3u);
  EXPECT_EQ(
      std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()),
      1);
}

TEST(PcdWrite, RefusesMisalignedIntensityAndMissingFolder) {
  test::TempDir dir;
  PointCloud bad = test::makeCloud(4, true);
  bad.intensity.pop_back();
  test::expectErrorAbout(dir / "bad.pcd", "3 intensities", [&] { writePcd(dir / "bad.pcd", bad); });
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.pcd"));
  test::expectErrorAbout(dir / "no" / "out.pcd", "folder does not exist",
                         [&] { writePcd(dir / "no" / "out.pcd", test::makeCloud(1, false)); });
}

TEST(PcdWrite, CompressedIsSmallerForStructuredData) {
  test::TempDir dir;
  PointCloud grid;
  for (int i = 0; i < 4000; ++i)
    grid.add(Vec3f(static_cast<float>(i % 40), static_cast<float>(i / 40), 0.0f), 7.0f);
  writePcd(dir / "b.pcd", grid, PcdEncoding::Binary);
  writePcd(dir / "c.pcd", grid, PcdEncoding::BinaryCompressed);
  EXPECT_LT(std::filesystem::file_size(dir / "c.pcd"), std::filesystem::file_size(dir / "b.pcd") / 2);
  test::expectSameCloud(grid, readPcd(dir / "c.pcd"));
}

}  // namespace
}  // namespace hba::io
