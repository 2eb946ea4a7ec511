// Reading PCD files written by PCL (tests/data/pcd, see its README).
#include <gtest/gtest.h>

#include <cmath>

#include "hba/io/pcd.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {
using test::pcdFixture;

constexpr std::size_t kCutPoints = 209;  // hku1 scan 0, 11 <= x <= 12

TEST(PcdRead, AllThreeEncodingsGiveIdenticalPoints) {
  const PointCloud binary = readPcd(pcdFixture("hku1_cut_binary.pcd"));
  ASSERT_EQ(binary.size(), kCutPoints);
  ASSERT_TRUE(binary.hasIntensity());
  for (const Vec3f& p : binary.points) {
    EXPECT_GE(p.x(), 11.0f);
    EXPECT_LE(p.x(), 12.0f);
  }
  test::expectSameCloud(binary, readPcd(pcdFixture("hku1_cut_ascii.pcd")));
  test::expectSameCloud(binary, readPcd(pcdFixture("hku1_cut_binary_compressed.pcd")));
}

TEST(PcdRead, FirstPointMatchesTheAsciiText) {
  // "11.230032 -1.0621866 0.492625773 17" is the first data line of the ascii file.
  const PointCloud cloud = readPcd(pcdFixture("hku1_cut_binary_compressed.pcd"));
  ASSERT_FALSE(cloud.empty());
  EXPECT_EQ(cloud.points[0], Vec3f(11.230032f, -1.0621866f, 0.492625773f));
  EXPECT_EQ(cloud.intensity[0], 17.0f);
}

TEST(PcdRead, SkipsNormalFieldsBeforeXyz) {
  const PointCloud plain = readPcd(pcdFixture("hku1_cut_binary.pcd"));
  for (const char* name : {"normals_ascii.pcd", "normals_binary.pcd", "normals_binary_compressed.pcd"}) {
    SCOPED_TRACE(name);
    test::expectSameCloud(plain, readPcd(pcdFixture(name)));
  }
}

TEST(PcdRead, SkipsAnArrayFieldWithCount33) {
  const PcdHeader header = readPcdHeader(pcdFixture("fpfh_binary.pcd"));
  ASSERT_EQ(header.fields.front().name, "fpfh");
  ASSERT_EQ(header.fields.front().count, 33);
  const PointCloud binary = readPcd(pcdFixture("fpfh_binary.pcd"));
  EXPECT_EQ(binary.size(), header.points);
  EXPECT_TRUE(binary.hasIntensity());
  test::expectSameCloud(binary, readPcd(pcdFixture("fpfh_binary_compressed.pcd")));
  for (const Vec3f& p : binary.points) {
    EXPECT_GE(p.x(), 11.0f);
    EXPECT_LE(p.x(), 11.2f);
  }
}

TEST(PcdRead, OrganizedCloudDropsItsNanHoles) {
  const PcdHeader header = readPcdHeader(pcdFixture("organized_binary.pcd"));
  EXPECT_EQ(header.width, 8u);
  EXPECT_EQ(header.height, 6u);
  EXPECT_EQ(header.points, 48u);
  const PointCloud cloud = readPcd(pcdFixture("organized_binary.pcd"));
  EXPECT_EQ(cloud.size(), 44u);        // the depth image has a 2 x 2 hole
  EXPECT_FALSE(cloud.hasIntensity());  // rgb is skipped, not taken for intensity
  for (const Vec3f& p : cloud.points) EXPECT_TRUE(p.allFinite());
  test::expectSameCloud(cloud, readPcd(pcdFixture("organized_ascii.pcd")));
  test::expectSameCloud(cloud, readPcd(pcdFixture("organized_binary_compressed.pcd")));
}

TEST(PcdRead, Float64FieldsBecomeTheSameFloats) {
  const PcdHeader header = readPcdHeader(pcdFixture("float64_binary.pcd"));
  ASSERT_EQ(header.fields[0].size, 8);
  const PointCloud doubles = readPcd(pcdFixture("float64_binary.pcd"));
  ASSERT_EQ(doubles.size(), 14u);
  test::expectSameCloud(doubles, readPcd(pcdFixture("float64_ascii.pcd")));
  test::expectSameCloud(doubles, readPcd(pcdFixture("float64_binary_compressed.pcd")));
  // The same text values as the first 14 float32 points of the cut.
  const PointCloud floats = readPcd(pcdFixture("hku1_cut_ascii.pcd"));
  for (std::size_t i = 0; i < doubles.size(); ++i) {
    EXPECT_EQ(doubles.points[i], floats.points[i]) << i;
    EXPECT_EQ(doubles.intensity[i], floats.intensity[i]) << i;
  }
}

TEST(PcdHeaderRead, ReportsFieldsCountsAndEncoding) {
  const PcdHeader header = readPcdHeader(pcdFixture("hku1_cut_binary_compressed.pcd"));
  ASSERT_EQ(header.fields.size(), 4u);
  EXPECT_EQ(header.fields[3].name, "intensity");
  EXPECT_EQ(header.fields[3].type, 'F');
  EXPECT_EQ(header.width, kCutPoints);
  EXPECT_EQ(header.height, 1u);
  EXPECT_EQ(header.points, kCutPoints);
  EXPECT_EQ(header.encoding, PcdEncoding::BinaryCompressed);
  EXPECT_EQ(readPcdHeader(pcdFixture("hku1_cut_ascii.pcd")).encoding, PcdEncoding::Ascii);
  EXPECT_EQ(readPcdHeader(pcdFixture("hku1_cut_binary.pcd")).encoding, PcdEncoding::Binary);
}

TEST(PcdHeaderRead, DataOffsetIsTheFirstByteAfterTheDataLine) {
  const std::string text = test::readText(pcdFixture("hku1_cut_binary.pcd"));
  const PcdHeader header = readPcdHeader(pcdFixture("hku1_cut_binary.pcd"));
  EXPECT_EQ(header.data_offset, text.find("DATA binary\n") + std::string("DATA binary\n").size());
}

}  // namespace
}  // namespace hba::io
