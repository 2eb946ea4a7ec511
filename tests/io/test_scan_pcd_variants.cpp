// PCD header and field variants seen in the wild, as hand-made files.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>

#include "hba/io/pcd.hpp"
#include "test_log_capture.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

template <typename T>
void append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

PointCloud readPcdText(const std::string& content) {
  test::TempDir dir;
  test::writeText(dir / "cloud.pcd", content);
  return readPcd(dir / "cloud.pcd");
}

TEST(PcdVariants, CommentsCrlfLowercaseKeywordsAndNoViewpoint) {
  const PointCloud cloud = readPcdText(
      "# made by some tool\r\nversion .7\r\n# fields follow\r\nfields x y z\r\nsize 4 4 4\r\n"
      "type f f f\r\ncount 1 1 1\r\nwidth 2\r\nheight 1\r\npoints 2\r\nDATA ASCII\r\n"
      "1 2 3\r\n4.5 -5 6e1\r\n");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.hasIntensity());
  EXPECT_EQ(cloud.points[1], Vec3f(4.5f, -5.0f, 60.0f));
}

TEST(PcdVariants, MissingCountHeightAndPointsDefaultSensibly) {
  const PointCloud cloud =
      readPcdText("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nDATA ascii\n0 0 0\n1 1 1\n2 2 2\n");
  EXPECT_EQ(cloud.size(), 3u);
}

TEST(PcdVariants, MissingWidthIsTakenFromPoints) {
  const PointCloud cloud =
      readPcdText("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 2\nDATA ascii\n0 0 0\n1 1 1\n");
  EXPECT_EQ(cloud.size(), 2u);
}

TEST(PcdVariants, IntegerIntensityOfAnyWidthBecomesFloat) {
  for (const char* type : {"U 1", "U 2", "I 4", "U 8", "I 2"}) {
    SCOPED_TRACE(type);
    std::string content = "FIELDS x y z intensity\nSIZE 4 4 4 " + std::string(type + 2) + "\nTYPE F F F " +
                          std::string(1, type[0]) + "\nWIDTH 1\nDATA binary\n";
    append(content, 1.0f);
    append(content, 2.0f);
    append(content, 3.0f);
    const int size = type[2] - '0';
    const std::uint64_t value = 200;
    content.append(reinterpret_cast<const char*>(&value), static_cast<std::size_t>(size));
    const PointCloud cloud = readPcdText(content);
    ASSERT_EQ(cloud.size(), 1u);
    EXPECT_EQ(cloud.intensity[0], 200.0f);
  }
}

TEST(PcdVariants, PaddingFieldsAndArraysAreSkippedInBinary) {
  // x y z _ (padding, COUNT 4) intensity ring t: a Velodyne-style layout.
  std::string content =
      "FIELDS x y z _ intensity ring t\nSIZE 4 4 4 1 4 2 8\nTYPE F F F U F U F\n"
      "COUNT 1 1 1 4 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA binary\n";
  for (int i = 0; i < 2; ++i) {
    append(content, 1.5f + static_cast<float>(i));
    append(content, -2.0f);
    append(content, 3.25f);
    content.append(4, '\x7f');  // padding bytes must not leak into values
    append(content, 9.0f + static_cast<float>(i));
    append(content, std::uint16_t{7});
    append(content, 0.125);
  }
  const PointCloud cloud = readPcdText(content);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Vec3f(2.5f, -2.0f, 3.25f));
  EXPECT_EQ(cloud.intensity[1], 10.0f);
}

TEST(PcdVariants, AsciiSkipsArrayValuesAndKeepsIntensity) {
  const PointCloud cloud = readPcdText(
      "FIELDS h x y z intensity\nSIZE 4 4 4 4 2\nTYPE F F F F U\nCOUNT 3 1 1 1 1\nWIDTH 1\n"
      "DATA ascii\n7 8 9 1 2 3 40\n");
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.points[0], Vec3f(1, 2, 3));
  EXPECT_EQ(cloud.intensity[0], 40.0f);
}

TEST(PcdVariants, NanAndInfPointsAreDroppedInEveryEncoding) {
  const std::string ascii =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4\nDATA ascii\n"
      "1 1 1\nnan nan nan\n2 inf 2\n3 3 3\n";
  EXPECT_EQ(readPcdText(ascii).size(), 2u);
  std::string binary = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nDATA binary\n";
  for (const float v :
       {1.0f, std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
    append(binary, 0.0f);
    append(binary, v);
    append(binary, 0.0f);
  }
  EXPECT_EQ(readPcdText(binary).size(), 1u);
}

TEST(PcdVariants, TrailingBytesAfterTheDataAreIgnored) {
  // PCL pads its binary files to a page boundary.
  std::string content = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nDATA binary\n";
  append(content, 1.0f);
  append(content, 2.0f);
  append(content, 3.0f);
  content.append(100, '\0');
  EXPECT_EQ(readPcdText(content).size(), 1u);
}

TEST(PcdVariants, HeaderLongerThanTheFirstHeaderReadIsFound) {
  // readPcdHeader first reads 4 KiB; a longer header needs its second read.
  std::string comments;
  while (comments.size() < 6000) comments += "# a tool that writes a long history into its header\n";
  test::TempDir dir;
  test::writeText(dir / "long.pcd",
                  comments + "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n");
  const PcdHeader header = readPcdHeader(dir / "long.pcd");
  EXPECT_EQ(header.points, 1u);
  EXPECT_EQ(header.data_offset, test::readText(dir / "long.pcd").size() - 6);
  EXPECT_EQ(readPcd(dir / "long.pcd").size(), 1u);
}

TEST(PcdVariants, EmptyCloudReadsAsEmpty) {
  for (const char* data : {"ascii", "binary", "binary_compressed"}) {
    SCOPED_TRACE(data);
    const PointCloud cloud =
        readPcdText("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA " +
                    std::string(data) + "\n");
    EXPECT_TRUE(cloud.empty());
  }
}

// Issue 57 item 17: keyframes written with WIDTH 0 HEIGHT 0 and the count in
// POINTS alone (the data exactly POINTS records) were refused as
// inconsistent. Read as PCL reads them, one row, with one warning a folder.
TEST(PcdVariants, ZeroByZeroGridWithPointsIsOneRowWarnedOncePerFolder) {
  const test::LogCapture log;
  test::TempDir dir;
  const std::string header =
      "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\n"
      "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 0\nHEIGHT 0\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA binary\n";
  std::string data;
  for (int i = 0; i < 3; ++i) {
    for (const float value : {1.0f + static_cast<float>(i), 2.0f, 3.0f, 7.0f}) append(data, value);
  }
  for (int k = 0; k < 4; ++k)
    test::writeText(dir / ("keyframe_" + std::to_string(k) + ".pcd"), header + data);
  for (int k = 0; k < 4; ++k) {
    const PointCloud cloud = readPcd(dir / ("keyframe_" + std::to_string(k) + ".pcd"));
    ASSERT_EQ(cloud.size(), 3u);
    EXPECT_EQ(cloud.points[2], Vec3f(3.0f, 2.0f, 3.0f));
    EXPECT_EQ(readPcdHeader(dir / ("keyframe_" + std::to_string(k) + ".pcd")).points, 3u);
  }
  const std::string text = log.text();
  const std::string warning = "WIDTH 0 HEIGHT 0 but POINTS 3: read as one row of 3 points, as PCL reads it";
  EXPECT_NE(text.find((dir / "keyframe_0.pcd").string() + ": the header says " + warning), std::string::npos)
      << text;
  EXPECT_EQ(text.find(warning), text.rfind(warning)) << "once per folder:\n" << text;

  // Its data is still checked against POINTS.
  test::writeText(dir / "short.pcd", header + data.substr(0, 40));
  EXPECT_THROW(readPcd(dir / "short.pcd"), Error);
}

}  // namespace
}  // namespace hba::io
