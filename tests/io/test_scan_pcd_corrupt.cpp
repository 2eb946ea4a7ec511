// Every corrupt or lying PCD gives an hba::Error naming the file and the
// problem: never a crash, a hang, or a cloud of garbage.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "hba/io/pcd.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

const std::string kXyzHeader = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

template <typename T>
std::string bytesOf(T value) {
  std::string out(sizeof(T), '\0');
  std::memcpy(&out[0], &value, sizeof(T));
  return out;
}

std::string floats(std::initializer_list<float> values) {
  std::string out;
  for (const float v : values) out += bytesOf(v);
  return out;
}

// A binary_compressed block: the two sizes, then the LZF bytes.
std::string compressedBlock(std::uint32_t compressed, std::uint32_t raw, const std::string& lzf) {
  return bytesOf(compressed) + bytesOf(raw) + lzf;
}

// One LZF literal run (control byte n-1, then n <= 32 bytes): valid LZF by hand.
std::string lzfLiteral(const std::string& raw) {
  return std::string(1, static_cast<char>(raw.size() - 1)) + raw;
}

struct CorruptCase {
  const char* name;
  std::string content;
  const char* problem;  // expected in the message
};

std::vector<CorruptCase> corruptCases() {
  const std::string two_points = floats({1, 2, 3, 4, 5, 6});
  return {
      {"empty", "", "empty file"},
      {"no_data_line", kXyzHeader + "WIDTH 1\n", "without a DATA line"},
      {"not_pcd", "ply\nformat ascii 1.0\n", "not a PCD header"},
      {"unknown_type", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F X\nWIDTH 1\nDATA binary\n" + floats({1, 2, 3}),
       "unknown TYPE"},
      {"size_not_type", "FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nWIDTH 1\nDATA binary\n" + floats({1, 2, 3}),
       "SIZE 2 does not fit TYPE F"},
      {"integer_size_3", "FIELDS x y z i\nSIZE 4 4 4 3\nTYPE F F F U\nWIDTH 1\nDATA binary\n", "SIZE 3"},
      {"size_list_short", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA binary\n", "SIZE lists 2"},
      {"count_zero", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 0 1\nWIDTH 1\nDATA ascii\n", "COUNT 0"},
      {"xyz_array", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 3 1 1\nWIDTH 1\nDATA ascii\n", "COUNT 3"},
      {"no_z", "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA binary\n" + floats({1, 2}), "no x, y and z"},
      {"duplicate_x", "FIELDS x y z x\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 1\nDATA ascii\n1 2 3 4\n",
       "appears twice"},
      {"unknown_encoding", kXyzHeader + "WIDTH 1\nDATA zip\n", "unknown DATA encoding"},
      {"points_vs_grid",
       kXyzHeader + "WIDTH 2\nHEIGHT 1\nPOINTS 3\nDATA binary\n" + floats({1, 2, 3, 4, 5, 6, 7, 8, 9}),
       "WIDTH x HEIGHT = 2 but POINTS = 3"},
      {"grid_overflow", kXyzHeader + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA binary\n", "overflows"},
      {"negative_width", kXyzHeader + "WIDTH -5\nDATA binary\n", "must not be negative"},
      {"huge_number", kXyzHeader + "WIDTH 99999999999999999999999\nDATA binary\n", "fits 64 bits"},
      {"data_size_overflow", kXyzHeader + "WIDTH 2000000000000000000\nDATA binary\n", "overflows"},
      {"binary_truncated", kXyzHeader + "WIDTH 2\nDATA binary\n" + floats({1, 2, 3, 4}), "truncated"},
      {"points_lie_binary", kXyzHeader + "WIDTH 1000000\nDATA binary\n" + two_points, "truncated"},
      {"size_lies", "FIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nWIDTH 2\nDATA binary\n" + two_points, "truncated"},
      {"ascii_truncated", kXyzHeader + "WIDTH 3\nDATA ascii\n1 2 3\n4 5 6\n", "truncated"},
      {"ascii_huge_points", kXyzHeader + "WIDTH 100000000000000\nDATA ascii\n1 2 3\n", "truncated"},
      {"ascii_extra_points", kXyzHeader + "WIDTH 1\nDATA ascii\n1 2 3\n4 5 6\n", "more points"},
      {"ascii_garbage", kXyzHeader + "WIDTH 1\nDATA ascii\n1 abc 3\n", "'abc' is not a number"},
      {"ascii_short_line", kXyzHeader + "WIDTH 1\nDATA ascii\n1 2\n", "2 values, but the fields need 3"},
      {"compressed_no_sizes", kXyzHeader + "WIDTH 2\nDATA binary_compressed\n\x10\x00", "sizes are missing"},
      {"compressed_raw_size_lies",
       kXyzHeader + "WIDTH 2\nDATA binary_compressed\n" + compressedBlock(25, 30, lzfLiteral(two_points)),
       "inflates to 30 bytes"},
      {"compressed_size_lies",
       kXyzHeader + "WIDTH 2\nDATA binary_compressed\n" + compressedBlock(500, 24, lzfLiteral(two_points)),
       "truncated"},
      {"compressed_garbage",
       kXyzHeader + "WIDTH 2\nDATA binary_compressed\n" + compressedBlock(20, 24, std::string(20, '\xff')),
       "corrupt compressed data"},
      {"compressed_short_output",
       kXyzHeader + "WIDTH 2\nDATA binary_compressed\n" +
           compressedBlock(13, 24, lzfLiteral(floats({1, 2, 3}))),
       "corrupt compressed data"},
      {"compressed_impossible_ratio",
       kXyzHeader + "WIDTH 100000000\nDATA binary_compressed\n" +
           compressedBlock(4, 1200000000, std::string("\x01\x00\x00\x00", 4)),
       "cannot hold"},
  };
}

TEST(PcdCorrupt, EveryCaseThrowsAnErrorNamingTheFileAndProblem) {
  test::TempDir dir;
  for (const CorruptCase& c : corruptCases()) {
    SCOPED_TRACE(c.name);
    const auto path = dir / (std::string(c.name) + ".pcd");
    test::writeText(path, c.content);
    test::expectErrorAbout(path, c.problem, [&] { readPcd(path); });
  }
}

TEST(PcdCorrupt, HeaderOnlyReadRejectsBadHeadersToo) {
  test::TempDir dir;
  for (const char* name : {"empty", "not_pcd", "unknown_type", "points_vs_grid", "grid_overflow",
                           "negative_width", "huge_number"}) {
    SCOPED_TRACE(name);
    for (const CorruptCase& c : corruptCases()) {
      if (c.name != std::string(name)) continue;
      const auto path = dir / (c.name + std::string(".pcd"));
      test::writeText(path, c.content);
      test::expectErrorAbout(path, c.problem, [&] { readPcdHeader(path); });
    }
  }
}

TEST(PcdCorrupt, HandMadeCompressedBlockIsColumnMajor) {
  // The valid counterpart of the cases above: x0 x1 y0 y1 z0 z1 in one literal run.
  test::TempDir dir;
  const std::string columns = floats({1, 4, 2, 5, 3, 6});
  test::writeText(dir / "ok.pcd", kXyzHeader + "WIDTH 2\nDATA binary_compressed\n" +
                                      compressedBlock(25, 24, lzfLiteral(columns)));
  const PointCloud cloud = readPcd(dir / "ok.pcd");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Vec3f(1, 2, 3));
  EXPECT_EQ(cloud.points[1], Vec3f(4, 5, 6));
}

TEST(PcdCorrupt, MissingFileAndDirectoryAreNamed) {
  test::TempDir dir;
  test::expectErrorAbout(dir / "absent.pcd", "no such file", [&] { readPcd(dir / "absent.pcd"); });
  test::expectErrorAbout(dir / "absent.pcd", "no such file", [&] { readPcdHeader(dir / "absent.pcd"); });
  std::filesystem::create_directory(dir / "folder.pcd");
  test::expectErrorAbout(dir / "folder.pcd", "is a folder, not a file", [&] { readPcd(dir / "folder.pcd"); });
  test::expectErrorAbout(dir / "folder.pcd", "is a folder, not a file",
                         [&] { readPcdHeader(dir / "folder.pcd"); });
}

TEST(PcdCorrupt, LongFileWithoutHeaderIsRejectedAfterABoundedScan) {
  test::TempDir dir;
  std::string comments;
  while (comments.size() < 200000) comments += "# not a header, just a very long comment block\n";
  test::writeText(dir / "comments.pcd", comments);
  test::expectErrorAbout(dir / "comments.pcd", "no DATA line in the first",
                         [&] { readPcd(dir / "comments.pcd"); });
  test::expectErrorAbout(dir / "comments.pcd", "no DATA line in the first",
                         [&] { readPcdHeader(dir / "comments.pcd"); });
}

TEST(PcdCorrupt, EveryTruncationOfARealFileFailsCleanlyOrReadsFewerBytes) {
  // Cut the PCL-written files at every length: each prefix either throws
  // hba::Error or (for cuts inside trailing padding) reads the full cloud.
  test::TempDir dir;
  for (const char* name : {"hku1_cut_binary.pcd", "hku1_cut_binary_compressed.pcd", "hku1_cut_ascii.pcd"}) {
    SCOPED_TRACE(name);
    const std::string full = test::readText(test::pcdFixture(name));
    const PointCloud expected = readPcd(test::pcdFixture(name));
    for (std::size_t length = 0; length < full.size(); length += test::truncationStep(length)) {
      // A fresh file each time: rewriting one in place makes ext4 flush it on close.
      std::filesystem::remove(dir / "cut.pcd");
      test::writeText(dir / "cut.pcd", full.substr(0, length));
      try {
        const PointCloud cloud = readPcd(dir / "cut.pcd");
        ASSERT_EQ(cloud.size(), expected.size()) << "length " << length;
      } catch (const Error& error) {
        ASSERT_NE(std::string(error.what()).find("cut.pcd: "), std::string::npos);
      }
    }
  }
}

}  // namespace
}  // namespace hba::io
