// LAS files written by other software (PDAL's, laspy's and laz-perf's test
// data in ../shared/data/las: LAS 1.2 to 1.4, point formats 0 1 2 3 6 7, UTM
// offsets, a 1.4 file whose legacy count is 0, junk bytes between the VLRs
// and the points, name fields without a NUL) read against the facts their
// expected.json lists. Skipped when ../shared is absent.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>

#include "hba/io/las.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/wide_cloud.hpp"
#include "test_las_bytes.hpp"
#include "test_log_capture.hpp"
#include "test_support.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

fs::path lasDir() { return test::sharedDataDir() / "las"; }

json expectedFacts() {
  std::ifstream in(lasDir() / "expected.json");
  return json::parse(in);
}

Vec3 vec3(const json& values) {
  return {values[0].get<double>(), values[1].get<double>(), values[2].get<double>()};
}

struct Bounds {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = -Vec3::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
};

// Within half the file's scale on every axis: the stored integer is the one
// expected.json names.
void expectWithinHalfScale(const Vec3& expected, const Vec3& actual, const Vec3& scale,
                           const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(std::abs(actual[a] - expected[a]), scale[a] / 2) << what << " axis " << a;
  }
}

class LasThirdParty : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(lasDir() / "expected.json")) GTEST_SKIP() << lasDir() << " is absent";
  }
};

TEST_F(LasThirdParty, HeadersGiveVersionFormatCountScaleAndOffset) {
  for (const json& file : expectedFacts()) {
    const std::string name = file["file"];
    SCOPED_TRACE(name);
    const LasHeader header = readLasHeader(lasDir() / name);
    EXPECT_EQ(std::to_string(header.version_major) + "." + std::to_string(header.version_minor),
              file["las_version"].get<std::string>());
    EXPECT_EQ(header.point_format, file["point_format"].get<int>());
    EXPECT_EQ(header.record_length, file["record_length"].get<int>());
    EXPECT_EQ(header.point_data_offset, file["offset_to_point_data"].get<std::uint32_t>());
    EXPECT_EQ(header.point_count, file["point_count"].get<std::uint64_t>());
    EXPECT_EQ(header.scale, vec3(file["scale"]));
    EXPECT_EQ(header.offset, vec3(file["offset"]));
    EXPECT_EQ(header.min, vec3(file["header_bounds"]["min"]));
    EXPECT_EQ(header.max, vec3(file["header_bounds"]["max"]));
    // At most 32 bytes, spaces kept, when the field has no NUL.
    EXPECT_EQ(header.generating_software, file["generating_software"].get<std::string>());
  }
}

// readScanWide keeps LAS coordinates as stored: every file to half its
// scale, 1e-7 degrees included.
TEST_F(LasThirdParty, WideReadGivesCountsPointsBoundsAndIntensities) {
  for (const json& file : expectedFacts()) {
    const std::string name = file["file"];
    SCOPED_TRACE(name);
    const Vec3 scale = vec3(file["scale"]);
    const WideCloud cloud = readScanWide(lasDir() / name);
    ASSERT_EQ(cloud.size(), file["point_count"].get<std::size_t>());
    ASSERT_TRUE(cloud.hasIntensity());
    for (std::size_t i = 0; i < file["first_points"].size(); ++i) {
      expectWithinHalfScale(vec3(file["first_points"][i]), cloud.world(i), scale,
                            "point " + std::to_string(i));
      EXPECT_EQ(cloud.intensity[i], file["first_intensities"][i].get<float>()) << "point " << i;
    }
    Bounds bounds;
    for (std::size_t i = 0; i < cloud.size(); ++i) bounds.add(cloud.world(i));
    expectWithinHalfScale(vec3(file["bounds"]["min"]), bounds.min, scale, "min");
    expectWithinHalfScale(vec3(file["bounds"]["max"]), bounds.max, scale, "max");
  }
}

// hba's own clouds hold each stored coordinate rounded once to a float
// relative to the cloud's origin: to half the scale in the five files in
// metres, to a float step (2e-6) in the one in degrees at 1e-7 (readScanWide
// keeps those).
TEST_F(LasThirdParty, CloudReadIsTheStoredValuesAsFloatsFromAnOrigin) {
  for (const json& file : expectedFacts()) {
    const std::string name = file["file"];
    SCOPED_TRACE(name);
    const PointCloud cloud = readScan(lasDir() / name);
    const WideCloud wide = readScanWide(lasDir() / name);
    ASSERT_EQ(cloud.size(), file["point_count"].get<std::size_t>());
    ASSERT_EQ(cloud.size(), wide.size());
    EXPECT_EQ(cloud.intensity, wide.intensity);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      ASSERT_EQ(cloud.points[i], (wide.points[i] - cloud.origin).cast<float>()) << "point " << i;
    }
    if (name == "epsg_4326.las") continue;
    const Vec3 scale = vec3(file["scale"]);
    for (std::size_t i = 0; i < file["first_points"].size(); ++i) {
      expectWithinHalfScale(vec3(file["first_points"][i]), cloud.world(i), scale,
                            "point " + std::to_string(i));
    }
    Bounds bounds;
    for (std::size_t i = 0; i < cloud.size(); ++i) bounds.add(cloud.world(i));
    expectWithinHalfScale(vec3(file["bounds"]["min"]), bounds.min, scale, "min");
    expectWithinHalfScale(vec3(file["bounds"]["max"]), bounds.max, scale, "max");
  }
}

// point-color.las (LAS 1.2) with its point count zeroed, as some writers
// leave it: the 1065 records that follow the header are read, with a
// warning naming the file.
TEST_F(LasThirdParty, ZeroPointCountWithRecordsFollowingReadsThemWithAWarning) {
  test::TempDir dir;
  std::string bytes = test::readText(lasDir() / "point-color.las");
  test::putBytes<std::uint32_t>(bytes, 107, 0);
  const fs::path copy = dir / "count_zero.las";
  test::writeText(copy, bytes);
  const test::LogCapture log;
  const PointCloud cloud = readScan(copy);
  const PointCloud original = readScan(lasDir() / "point-color.las");
  ASSERT_EQ(cloud.size(), 1065u);
  EXPECT_EQ(cloud.points, original.points);
  EXPECT_EQ(cloud.origin, original.origin);
  EXPECT_EQ(readLasHeader(copy).point_count, 1065u);
  EXPECT_NE(log.text().find(copy.string() + ": the header counts 0 points, but 27690 bytes of point records"),
            std::string::npos)
      << log.text();
  EXPECT_NE(log.text().find("reading the 1065 records of 26 bytes"), std::string::npos) << log.text();
}

}  // namespace
}  // namespace hba::io
