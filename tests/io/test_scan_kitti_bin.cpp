// KITTI velodyne .bin reading and writing.
#include <gtest/gtest.h>

#include <cstring>

#include "hba/io/kitti_bin.hpp"
#include "hba/io/pcd.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

TEST(KittiBin, FixtureMatchesThePcdItWasPackedFrom) {
  test::expectSameCloud(readPcd(test::pcdFixture("hku1_cut_ascii.pcd")),
                        readKittiBin(test::binFixture("hku1_cut.bin")));
}

TEST(KittiBin, RoundTripsExactly) {
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(500, true);
  writeKittiBin(dir / "000000.bin", cloud);
  EXPECT_EQ(std::filesystem::file_size(dir / "000000.bin"), 500u * 16u);
  test::expectSameCloud(cloud, readKittiBin(dir / "000000.bin"));
}

TEST(KittiBin, CloudWithoutIntensityGetsZero) {
  test::TempDir dir;
  writeKittiBin(dir / "a.bin", test::makeCloud(3, false));
  const PointCloud back = readKittiBin(dir / "a.bin");
  ASSERT_EQ(back.intensity.size(), 3u);
  EXPECT_EQ(back.intensity[2], 0.0f);
}

TEST(KittiBin, DropsNonFinitePoints) {
  test::TempDir dir;
  const float records[8] = {1, 2, 3, 4, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1};
  test::writeText(dir / "nan.bin", std::string(reinterpret_cast<const char*>(records), sizeof(records)));
  EXPECT_EQ(readKittiBin(dir / "nan.bin").size(), 1u);
}

TEST(KittiBin, RejectsSizesThatAreNotWholeRecordsAndBadPaths) {
  test::TempDir dir;
  test::writeText(dir / "odd.bin", std::string(33, '\0'));
  test::expectErrorAbout(dir / "odd.bin", "not a multiple of 16", [&] { readKittiBin(dir / "odd.bin"); });
  test::expectErrorAbout(dir / "none.bin", "no such file", [&] { readKittiBin(dir / "none.bin"); });
  std::filesystem::create_directory(dir / "d.bin");
  test::expectErrorAbout(dir / "d.bin", "is a folder, not a file", [&] { readKittiBin(dir / "d.bin"); });
  test::writeText(dir / "empty.bin", "");
  EXPECT_TRUE(readKittiBin(dir / "empty.bin").empty());
}

// Scratch files (the pyramid's keyframes) hold exactly the bytes of a KITTI scan.
TEST(KittiBin, ScratchFilesHoldTheSameBytes) {
  test::TempDir dir;
  for (const bool with_intensity : {true, false}) {
    const PointCloud cloud = test::makeCloud(200, with_intensity);
    writeKittiBin(dir / "atomic.bin", cloud);
    writeScratchKittiBin(dir / "scratch.bin", cloud);
    EXPECT_EQ(test::readText(dir / "scratch.bin"), test::readText(dir / "atomic.bin"));
  }
  test::expectErrorAbout(dir / "none" / "a.bin", "cannot write",
                         [&] { writeScratchKittiBin(dir / "none" / "a.bin", test::makeCloud(1, true)); });
}

TEST(KittiBin, PointCountFromTheSizeAlone) {
  test::TempDir dir;
  writeKittiBin(dir / "a.bin", test::makeCloud(37, true));
  EXPECT_EQ(kittiBinPointCount(dir / "a.bin"), 37u);
  test::writeText(dir / "odd.bin", std::string(33, '\0'));
  test::expectErrorAbout(dir / "odd.bin", "not a multiple of 16",
                         [&] { kittiBinPointCount(dir / "odd.bin"); });
  test::expectErrorAbout(dir / "none.bin", "cannot read the file size",
                         [&] { kittiBinPointCount(dir / "none.bin"); });
}

}  // namespace
}  // namespace hba::io
