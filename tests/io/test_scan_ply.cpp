// PLY reading (files by PCL, VTK and hand-made variants) and writing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

template <typename T>
std::string bytesOf(T value, bool big_endian = false) {
  std::string out(sizeof(T), '\0');
  std::memcpy(&out[0], &value, sizeof(T));
  if (big_endian) std::reverse(out.begin(), out.end());
  return out;
}

PointCloud readPlyText(const std::string& content) {
  test::TempDir dir;
  test::writeText(dir / "cloud.ply", content);
  return readPly(dir / "cloud.ply");
}

TEST(PlyRead, PclBinaryPlyHasTheSamePointsAsThePcd) {
  const PointCloud pcd = readPcd(test::pcdFixture("hku1_cut_binary.pcd"));
  test::expectSameCloud(pcd, readPly(test::plyFixture("hku1_cut_binary.ply")));
}

TEST(PlyRead, PclAsciiPlyMatchesToItsPrintedDigits) {
  const PointCloud pcd = readPcd(test::pcdFixture("hku1_cut_binary.pcd"));
  const PointCloud ply = readPly(test::plyFixture("hku1_cut_ascii.ply"));
  test::expectNearCloud(pcd, ply, 1e-5f);  // PCL prints 8 significant digits
  EXPECT_EQ(pcd.intensity, ply.intensity);
}

TEST(PlyRead, MeshFacesAfterTheVerticesAreIgnored) {
  const PointCloud pcd = readPcd(test::pcdFixture("hku1_cut_binary.pcd"));
  const PointCloud ascii = readPly(test::plyFixture("mesh_ascii.ply"));
  EXPECT_FALSE(ascii.hasIntensity());
  test::expectNearCloud(pcd, ascii, 1e-3f);  // went through a 5-digit VTK file
  test::expectSameCloud(ascii, readPly(test::plyFixture("mesh_binary.ply")));
}

TEST(PlyRead, CloudCompareScalarIntensityAndOtherPropertyTypes) {
  const PointCloud cloud = readPlyText(
      "ply\nformat ascii 1.0\ncomment CloudCompare\nelement vertex 2\nproperty double x\n"
      "property int y\nproperty uchar red\nproperty float z\nproperty float scalar_Intensity\nend_header\n"
      "1.5 -2 255 3 0.25\n+4 5 0 6e-1 7\n");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Vec3f(1.5f, -2.0f, 3.0f));
  EXPECT_EQ(cloud.points[1], Vec3f(4.0f, 5.0f, 0.6f));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{0.25f, 7.0f}));
}

TEST(PlyRead, ElementsWithListsBeforeTheVerticesAreSkipped) {
  const std::string header_tail =
      "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
      "element empty 1000000000000\n"
      "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property list uint8 float extra\nproperty float intensity\nend_header\n";
  const PointCloud ascii = readPlyText("ply\nformat ascii 1.0\n" + header_tail +
                                       "3 0 1 2 9\n4 0 1 2 3 9\n1 2 3 2 0.5 0.5 10\n4 5 6 0 11\n");
  std::string binary = "ply\nformat binary_little_endian 1.0\n" + header_tail;
  binary += bytesOf<std::uint8_t>(3) + bytesOf(0) + bytesOf(1) + bytesOf(2) + bytesOf<std::uint8_t>(9);
  binary +=
      bytesOf<std::uint8_t>(4) + bytesOf(0) + bytesOf(1) + bytesOf(2) + bytesOf(3) + bytesOf<std::uint8_t>(9);
  binary += bytesOf(1.0f) + bytesOf(2.0f) + bytesOf(3.0f) + bytesOf<std::uint8_t>(2) + bytesOf(0.5f) +
            bytesOf(0.5f) + bytesOf(10.0f);
  binary += bytesOf(4.0f) + bytesOf(5.0f) + bytesOf(6.0f) + bytesOf<std::uint8_t>(0) + bytesOf(11.0f);
  for (const PointCloud& cloud : {ascii, readPlyText(binary)}) {
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud.points[1], Vec3f(4, 5, 6));
    EXPECT_EQ(cloud.intensity, (std::vector<float>{10.0f, 11.0f}));
  }
}

TEST(PlyRead, BigEndianIsSupported) {
  std::string content =
      "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty double y\n"
      "property short z\nproperty ushort intensity\nend_header\n";
  content += bytesOf(1.25f, true) + bytesOf(-2.5, true) + bytesOf<std::int16_t>(-3, true) +
             bytesOf<std::uint16_t>(300, true);
  const PointCloud cloud = readPlyText(content);
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.points[0], Vec3f(1.25f, -2.5f, -3.0f));
  EXPECT_EQ(cloud.intensity[0], 300.0f);
}

TEST(PlyWrite, RoundTripsExactlyInBothEncodings) {
  test::TempDir dir;
  for (const bool with_intensity : {true, false}) {
    const PointCloud cloud = test::makeCloud(700, with_intensity);
    for (const PlyEncoding encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian}) {
      writePly(dir / "out.ply", cloud, encoding);
      test::expectSameCloud(cloud, readPly(dir / "out.ply"));
    }
  }
}

struct CorruptPly {
  const char* name;
  std::string content;
  const char* problem;
};

TEST(PlyCorrupt, EveryCaseThrowsAnErrorNamingTheFileAndProblem) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string bin = "ply\nformat binary_little_endian 1.0\n";
  const std::vector<CorruptPly> cases = {
      {"empty", "", "empty file"},
      {"not_ply", "# .PCD v0.7\nFIELDS x y z\n", "not a PLY file"},
      {"no_format", "ply\nelement vertex 0\n" + xyz + "end_header\n", "no format line"},
      {"bad_format", "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown PLY format"},
      {"no_end_header", bin + "element vertex 1\n" + xyz, "no end_header"},
      {"bad_type", bin + "element vertex 1\nproperty float128 x\nend_header\n", "unknown PLY property type"},
      {"negative_count", bin + "element vertex -1\n" + xyz + "end_header\n", "negative count"},
      {"huge_count", bin + "element vertex 99999999999999999999999\n" + xyz + "end_header\n",
       "invalid count"},
      {"no_vertex", bin + "element face 0\nproperty list uchar int v\nend_header\n", "no vertex element"},
      {"no_z",
       bin + "element vertex 1\nproperty float x\nproperty float y\nend_header\n" + std::string(8, '\0'),
       "no x, y and z"},
      {"binary_truncated", bin + "element vertex 3\n" + xyz + "end_header\n" + std::string(20, '\0'),
       "truncated"},
      {"binary_count_overflow", bin + "element vertex 2000000000000000000\n" + xyz + "end_header\n",
       "overflows"},
      {"list_runs_past_end",
       bin + "element face 1\nproperty list uint int v\nelement vertex 0\n" + xyz + "end_header\n" +
           std::string("\xff\xff\xff\x0f", 4),
       "truncated"},
      {"negative_list_length",
       bin + "element face 1\nproperty list char int v\nelement vertex 0\n" + xyz + "end_header\n\xfe",
       "negative list length"},
      {"ascii_truncated", "ply\nformat ascii 1.0\nelement vertex 2\n" + xyz + "end_header\n1 2 3\n4 5\n",
       "truncated"},
      {"ascii_garbage", "ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n1 x 3\n",
       "'x' is not a number"},
  };
  test::TempDir dir;
  for (const CorruptPly& c : cases) {
    SCOPED_TRACE(c.name);
    const auto path = dir / (std::string(c.name) + ".ply");
    test::writeText(path, c.content);
    test::expectErrorAbout(path, c.problem, [&] { readPly(path); });
  }
  test::expectErrorAbout(dir / "none.ply", "no such file", [&] { readPly(dir / "none.ply"); });
}

TEST(PlyCorrupt, EveryTruncationOfARealFileFailsCleanly) {
  test::TempDir dir;
  for (const char* name : {"hku1_cut_binary.ply", "mesh_binary.ply", "hku1_cut_ascii.ply"}) {
    SCOPED_TRACE(name);
    const std::string full = test::readText(test::plyFixture(name));
    const std::size_t expected = readPly(test::plyFixture(name)).size();
    for (std::size_t length = 0; length < full.size(); length += test::truncationStep(length)) {
      std::filesystem::remove(dir / "cut.ply");  // fresh file: see the PCD truncation test
      test::writeText(dir / "cut.ply", full.substr(0, length));
      try {
        EXPECT_EQ(readPly(dir / "cut.ply").size(), expected) << "length " << length;
      } catch (const Error& error) {
        ASSERT_NE(std::string(error.what()).find("cut.ply: "), std::string::npos);
      }
    }
  }
}

}  // namespace
}  // namespace hba::io
