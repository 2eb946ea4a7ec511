// readScanWide / writeScanWide: float64 coordinates kept to the last bit
// through .pcd and .ply, to the millimetre through .las, and refused by .bin
// (float32 only) rather than rounded; float32 ones written as float32.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "hba/io/kitti_bin.hpp"
#include "hba/io/las.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/wide_cloud.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

// Survey points in UTM with sub-millimetre fractions: no float32 holds them.
WideCloud utmPoints(std::size_t n, bool with_intensity) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> metres(-500.0, 500.0);
  WideCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p(494428.61 + metres(random), 4877455.58 + metres(random), 130.0 + metres(random) / 50);
    if (with_intensity) {
      cloud.add(p, static_cast<float>(i % 200));
    } else {
      cloud.add(p);
    }
  }
  return cloud;
}

TEST(WideScan, PcdAndPlyKeepFloat64CoordinatesExactly) {
  test::TempDir dir;
  for (const bool with_intensity : {true, false}) {
    const WideCloud cloud = utmPoints(500, with_intensity);
    for (const char* name : {"map.pcd", "map.ply"}) {
      SCOPED_TRACE(std::string(name) + (with_intensity ? " with intensity" : ""));
      writeScanWide(dir / name, cloud);
      const WideCloud back = readScanWide(dir / name);
      EXPECT_EQ(back.points, cloud.points);
      EXPECT_EQ(back.intensity, cloud.intensity);
    }
  }
  EXPECT_NE(test::readText(dir / "map.pcd").find("SIZE 8 8 8\n"), std::string::npos);
  EXPECT_NE(test::readText(dir / "map.ply").find("property double x\n"), std::string::npos);
}

TEST(WideScan, FloatCoordinatesAreWrittenAsFloat32) {
  test::TempDir dir;
  WideCloud cloud;
  cloud.add(Vec3(1.5, -2.25, 1e-3f), 3.0f);
  cloud.add(Vec3(100.0, 0.1f, 7.0), 4.0f);
  writeScanWide(dir / "small.pcd", cloud);
  EXPECT_NE(test::readText(dir / "small.pcd").find("SIZE 4 4 4 4\n"), std::string::npos);
  EXPECT_EQ(readScanWide(dir / "small.pcd").points, cloud.points);
  // The same bytes as writeScan of the same floats.
  PointCloud narrow;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    narrow.add(cloud.points[i].cast<float>(), cloud.intensity[i]);
  writeScan(dir / "narrow.pcd", narrow);
  EXPECT_EQ(test::readText(dir / "small.pcd"), test::readText(dir / "narrow.pcd"));
  writeScanWide(dir / "small.bin", cloud);
  EXPECT_EQ(readScanWide(dir / "small.bin").points, cloud.points);
}

TEST(WideScan, LasKeepsMillimetres) {
  test::TempDir dir;
  const WideCloud cloud = utmPoints(500, true);
  writeScanWide(dir / "map.las", cloud);
  const WideCloud back = readScanWide(dir / "map.las");
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_LE((back.points[i] - cloud.points[i]).cwiseAbs().maxCoeff(), 0.0005 + 1e-9) << "point " << i;
  }
  EXPECT_EQ(back.intensity, cloud.intensity);
}

TEST(WideScan, BinRefusesWhatFloat32WouldRound) {
  test::TempDir dir;
  test::expectErrorAbout(dir / "map.bin", "cannot write point 0 (",
                         [&] { writeScanWide(dir / "map.bin", utmPoints(3, true)); });
  EXPECT_FALSE(std::filesystem::exists(dir / "map.bin"));
  // hba's own clouds too: a map with an origin was written without it.
  PointCloud map;
  map.origin = Vec3(494000.0, 4877000.0, 0.0);
  map.add(Vec3f(428.61f, 455.58f, 131.57f), 1.0f);
  test::expectErrorAbout(dir / "map.bin", "a .bin stores float32 x y z",
                         [&] { writeScan(dir / "map.bin", map); });
  map.origin = Vec3(1000.0, 0.0, 0.0);  // world coordinates that are floats
  writeKittiBin(dir / "near.bin", map);
  EXPECT_EQ(readKittiBin(dir / "near.bin").points.front(), Vec3f(1428.61f, 455.58f, 131.57f));
}

// float64 fields come back exactly; readScan rounds them to floats from an origin.
TEST(WideScan, ReadsFloat64FieldsExactly) {
  test::TempDir dir;
  const WideCloud cloud = utmPoints(50, true);
  writeScanWide(dir / "map.pcd", cloud);
  const PointCloud narrow = readScan(dir / "map.pcd");
  const WideCloud wide = readScanWide(dir / "map.pcd");
  EXPECT_EQ(wide.points, cloud.points);
  ASSERT_EQ(narrow.size(), wide.size());
  for (std::size_t i = 0; i < narrow.size(); ++i) {
    ASSERT_EQ(narrow.points[i], (wide.points[i] - narrow.origin).cast<float>()) << "point " << i;
  }
}

TEST(WideScan, DropsNonFinitePointsAsReadScanDoes) {
  test::TempDir dir;
  PointCloud cloud = test::makeCloud(5, true);
  cloud.points[2].y() = std::nanf("");
  writeScan(dir / "nan.pcd", cloud);
  const WideCloud wide = readScanWide(dir / "nan.pcd");
  const PointCloud narrow = readScan(dir / "nan.pcd");
  ASSERT_EQ(wide.size(), 4u);
  ASSERT_EQ(narrow.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(wide.points[i].cast<float>(), narrow.points[i]);
  EXPECT_EQ(wide.intensity, narrow.intensity);
}

}  // namespace
}  // namespace hba::io
