// LAS: hba's writer checked field by field against the specification's
// layout, round trips at UTM coordinates, and the reader on every version
// and point format built by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "hba/io/las.hpp"
#include "hba/io/scan_file.hpp"
#include "test_las_bytes.hpp"
#include "test_log_capture.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

constexpr std::size_t kHeader14 = 375;
constexpr std::size_t kRecord6 = 30;
// A stored coordinate is within half a millimetre (plus double rounding).
constexpr double kHalfMillimetre = 0.0005 + 1e-9;
// Read back, it is a float relative to the cloud's origin: within 64 m of
// it, that adds at most half a float step (4 micrometres).
constexpr double kHalfMillimetreAsFloat = kHalfMillimetre + 4e-6;

// A survey-like cloud 500 km east, 4500 km north: points with sub-millimetre
// fractions, integer intensities over the whole uint16 range.
PointCloud utmCloud(std::size_t n) {
  PointCloud cloud;
  cloud.origin = Vec3(500000.0, 4500000.0, 100.0);
  for (std::size_t i = 0; i < n; ++i) {
    const float t = static_cast<float>(i);
    cloud.add(Vec3f(40.0f * std::sin(0.37f * t) + 0.0001234f * t, -25.0f + 0.0173f * t, 3.0f * std::cos(t)),
              static_cast<float>((i * 977) % 65536));
  }
  return cloud;
}

std::size_t recordAt(std::size_t i) { return kHeader14 + i * kRecord6; }

TEST(Las, RoundTripKeepsMillimetresAtUtmCoordinates) {
  test::TempDir dir;
  const PointCloud cloud = utmCloud(2000);
  writeLas(dir / "utm.las", cloud);
  const PointCloud back = readLas(dir / "utm.las");
  ASSERT_EQ(back.size(), cloud.size());
  ASSERT_TRUE(back.hasIntensity());
  EXPECT_GT(back.origin.norm(), 1e6);  // kept relative to an origin, not rounded to floats
  double worst = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    worst = std::max(worst, (back.world(i) - cloud.world(i)).cwiseAbs().maxCoeff());
    ASSERT_EQ(back.intensity[i], cloud.intensity[i]) << "point " << i;
  }
  EXPECT_LE(worst, kHalfMillimetreAsFloat);
  // The file itself holds every coordinate to half a millimetre.
  const std::string bytes = test::readText(dir / "utm.las");
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double stored = test::getBytes<std::int32_t>(bytes, recordAt(i) + 4 * a) * 0.001 +
                            test::getBytes<double>(bytes, 155 + 8 * a);
      ASSERT_NEAR(stored, cloud.world(i)[a], kHalfMillimetre) << "point " << i << " axis " << a;
    }
  }
  EXPECT_GT(worst, 1e-5);  // the cloud's sub-millimetre parts were really rounded
}

TEST(Las, HeaderHoldsCountsBoundsScaleAndOffset) {
  test::TempDir dir;
  const PointCloud cloud = utmCloud(500);
  writeLas(dir / "h.las", cloud);
  const std::string bytes = test::readText(dir / "h.las");
  ASSERT_EQ(bytes.size(), kHeader14 + 500 * kRecord6);
  EXPECT_EQ(bytes.substr(0, 4), "LASF");
  EXPECT_EQ(bytes[24], 1);
  EXPECT_EQ(bytes[25], 4);
  EXPECT_EQ(bytes.substr(58, 4), "hba ");
  EXPECT_EQ(test::getBytes<std::uint16_t>(bytes, 94), kHeader14);
  EXPECT_EQ(test::getBytes<std::uint32_t>(bytes, 96), kHeader14);
  EXPECT_EQ(test::getBytes<std::uint32_t>(bytes, 100), 0u);  // no VLRs
  EXPECT_EQ(bytes[104], 6);
  EXPECT_EQ(test::getBytes<std::uint16_t>(bytes, 105), kRecord6);
  // Formats 6-10 leave the legacy counts zero; the 64-bit fields count.
  EXPECT_EQ(test::getBytes<std::uint32_t>(bytes, 107), 0u);
  for (int r = 0; r < 5; ++r) EXPECT_EQ(test::getBytes<std::uint32_t>(bytes, 111 + 4 * r), 0u);
  EXPECT_EQ(test::getBytes<std::uint64_t>(bytes, 247), 500u);
  EXPECT_EQ(test::getBytes<std::uint64_t>(bytes, 255), 500u);  // all first returns
  for (int r = 1; r < 15; ++r) EXPECT_EQ(test::getBytes<std::uint64_t>(bytes, 255 + 8 * r), 0u);

  Vec3 low = cloud.world(0), high = cloud.world(0);
  for (std::size_t i = 1; i < cloud.size(); ++i) {
    low = low.cwiseMin(cloud.world(i));
    high = high.cwiseMax(cloud.world(i));
  }
  for (int a = 0; a < 3; ++a) {
    SCOPED_TRACE(a);
    EXPECT_EQ(test::getBytes<double>(bytes, 131 + 8 * a), 0.001);
    const double offset = test::getBytes<double>(bytes, 155 + 8 * a);
    EXPECT_EQ(offset, std::round((low[a] + high[a]) / 2.0));  // the centre in whole metres
    EXPECT_NEAR(test::getBytes<double>(bytes, 179 + 16 * a), high[a], kHalfMillimetre);
    EXPECT_NEAR(test::getBytes<double>(bytes, 187 + 16 * a), low[a], kHalfMillimetre);
  }

  const LasHeader header = readLasHeader(dir / "h.las");
  EXPECT_EQ(header.point_count, 500u);
  EXPECT_EQ(header.point_format, 6);
  EXPECT_EQ(header.generating_software.rfind("hba ", 0), 0u) << header.generating_software;
  EXPECT_GT(header.generating_software.size(), 4u);  // carries the version
}

TEST(Las, RecordsCarryReturnScanIndexAndGpsTime) {
  test::TempDir dir;
  const PointCloud cloud = utmCloud(4);
  LasPointExtras extras;
  extras.scan_index = {0, 7, 65535, 70000};
  extras.gps_time = {0.5, 1.25, 1e9, -3.0};
  writeLas(dir / "x.las", cloud, extras);
  const std::string bytes = test::readText(dir / "x.las");
  const std::uint16_t expected_source[] = {0, 7, 65535, 65535};  // above 65535: saturated
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(static_cast<std::uint8_t>(bytes[recordAt(i) + 14]), 0x11);  // return 1 of 1
    EXPECT_EQ(test::getBytes<std::uint16_t>(bytes, recordAt(i) + 20), expected_source[i]);
    EXPECT_EQ(test::getBytes<double>(bytes, recordAt(i) + 22), extras.gps_time[i]);
  }
  // Without extras both fields are zero.
  writeLas(dir / "plain.las", cloud);
  const std::string plain = test::readText(dir / "plain.las");
  EXPECT_EQ(test::getBytes<std::uint16_t>(plain, recordAt(3) + 20), 0u);
  EXPECT_EQ(test::getBytes<double>(plain, recordAt(3) + 22), 0.0);
}

TEST(Las, IntensityIsRoundedAndClampedToUint16) {
  test::TempDir dir;
  PointCloud cloud;
  const float values[] = {-5.0f, 12.4f, 12.6f, 1e6f, std::nanf("")};
  for (const float v : values) cloud.add(Vec3f(1, 2, 3), v);
  writeLas(dir / "i.las", cloud);
  const PointCloud back = readLas(dir / "i.las");
  ASSERT_EQ(back.size(), 5u);
  EXPECT_EQ(back.intensity, (std::vector<float>{0.0f, 12.0f, 13.0f, 65535.0f, 0.0f}));
}

TEST(Las, EmptyCloudAndCloudWithoutIntensity) {
  test::TempDir dir;
  writeLas(dir / "empty.las", PointCloud{});
  EXPECT_EQ(readLasHeader(dir / "empty.las").point_count, 0u);
  EXPECT_TRUE(readLas(dir / "empty.las").empty());
  const PointCloud bare = test::makeCloud(10, false);
  writeLas(dir / "bare.las", bare);
  const PointCloud back = readLas(dir / "bare.las");
  EXPECT_EQ(back.intensity, std::vector<float>(10, 0.0f));  // LAS always has the field
  test::expectNearCloud(bare, back, 0.0005f + 1e-5f);
}

TEST(Las, WriterRefusesWhatItCannotStore) {
  test::TempDir dir;
  PointCloud cloud = test::makeCloud(3, true);
  LasPointExtras extras;
  extras.scan_index = {1, 2};
  test::expectErrorAbout(dir / "a.las", "3 points but 2 scan indices",
                         [&] { writeLas(dir / "a.las", cloud, extras); });
  extras = {};
  extras.gps_time = {1.0};
  test::expectErrorAbout(dir / "a.las", "3 points but 1 GPS times",
                         [&] { writeLas(dir / "a.las", cloud, extras); });
  cloud.points[1].x() = 5.0e6f;  // 5000 km from its neighbours: beyond int32 millimetres
  test::expectErrorAbout(dir / "a.las", "beyond what LAS int32 millimetres can hold",
                         [&] { writeLas(dir / "a.las", cloud); });
  cloud.points[1].x() = std::nanf("");
  test::expectErrorAbout(dir / "a.las", "not a finite coordinate", [&] { writeLas(dir / "a.las", cloud); });
  EXPECT_FALSE(std::filesystem::exists(dir / "a.las"));
}

// Every version and point format hba reads, with a VLR and extra bytes to skip.
TEST(Las, ReadsEveryVersionAndPointFormat) {
  test::TempDir dir;
  const std::vector<test::LasPointInts> points = {{100, -200, 300, 7}, {-5, 0, 123456, 65535}};
  const int min_length[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  for (int format = 0; format <= 10; ++format) {
    for (int minor = format > 5 ? 4 : 0; minor <= 4; ++minor) {
      SCOPED_TRACE("LAS 1." + std::to_string(minor) + " format " + std::to_string(format));
      test::LasSpec spec;
      spec.minor = minor;
      spec.format = format;
      spec.record_length = min_length[format] + (minor % 2) * 3;  // some with extra bytes
      spec.offset[0] = 500000.0;
      spec.offset[2] = -10.0;
      spec.vlr_payloads = {16, 0};
      spec.legacy_count = format <= 5;
      const auto path = dir / "f.las";
      test::writeText(path, test::lasBytes(spec, points));
      const PointCloud cloud = readLas(path);
      ASSERT_EQ(cloud.size(), 2u);
      EXPECT_NEAR(cloud.world(0).x(), 500001.0, 1e-6);
      EXPECT_NEAR(cloud.world(0).y(), -2.0, 1e-6);
      EXPECT_NEAR(cloud.world(1).z(), 1224.56, 1e-6);
      EXPECT_EQ(cloud.intensity, (std::vector<float>{7.0f, 65535.0f}));
    }
  }
}

// Writers that leave every point count at 0 still store the records after
// the header: they are read, with one warning naming the file.
TEST(Las, ZeroCountWithRecordsFollowingReadsThemWithAWarning) {
  test::TempDir dir;
  const std::vector<test::LasPointInts> points = {{100, -200, 300, 7}, {-5, 0, 123456, 65535}, {1, 2, 3, 4}};
  for (const int minor : {2, 4}) {
    SCOPED_TRACE("LAS 1." + std::to_string(minor));
    test::LasSpec spec;
    spec.minor = minor;
    spec.vlr_payloads = {16};
    spec.legacy_count = false;
    spec.wide_count = false;
    const auto path = dir / ("zero_" + std::to_string(minor) + ".las");
    test::writeText(path, test::lasBytes(spec, points));
    const test::LogCapture log;
    const PointCloud cloud = readLas(path);
    ASSERT_EQ(cloud.size(), 3u);
    EXPECT_NEAR(cloud.world(1).z(), 1234.56, 1e-4);
    EXPECT_EQ(cloud.intensity, (std::vector<float>{7.0f, 65535.0f, 4.0f}));
    EXPECT_EQ(readLasHeader(path).point_count, 3u);
    readLas(path);
    const std::string warning = path.string() + ": the header counts 0 points, but 84 bytes of point records";
    const std::string text = log.text();
    EXPECT_NE(text.find(warning), std::string::npos) << text;
    EXPECT_EQ(text.find(warning), text.rfind(warning)) << "warned twice about one file: " << text;
  }
}

// The bytes after the records are not records: a trailing part of one, the
// extended VLRs of LAS 1.4 (their start is in the header).
TEST(Las, ZeroCountReadsOnlyWholeRecordsBeforeExtendedVlrs) {
  test::TempDir dir;
  test::LasSpec spec;
  spec.minor = 4;
  spec.legacy_count = false;
  spec.wide_count = false;
  std::string bytes = test::lasBytes(spec, {{1, 2, 3, 4}, {5, 6, 7, 8}});
  const std::size_t records_end = bytes.size();
  bytes += std::string(60 + 28 * 3, 'e');  // an EVLR header and 3 records' worth of payload
  test::putBytes<std::uint64_t>(bytes, 235, records_end);
  test::putBytes<std::uint32_t>(bytes, 243, 1);
  test::writeText(dir / "evlr.las", bytes);
  EXPECT_EQ(readLas(dir / "evlr.las").size(), 2u);
  bytes.resize(records_end + 5);
  test::putBytes<std::uint32_t>(bytes, 243, 0);
  test::writeText(dir / "tail.las", bytes);
  const test::LogCapture log;
  EXPECT_EQ(readLas(dir / "tail.las").size(), 2u);
  EXPECT_NE(log.text().find("(5 bytes left over)"), std::string::npos) << log.text();
  bytes.resize(records_end - 56);  // less than one record after the header
  test::writeText(dir / "none.las", bytes);
  EXPECT_TRUE(readLas(dir / "none.las").empty());
}

TEST(Las, ScanFilesDispatchOnTheExtension) {
  test::TempDir dir;
  const PointCloud cloud = test::makeCloud(50, true);
  writeScan(dir / "s.LAS", cloud);
  EXPECT_TRUE(isScanFile(dir / "s.LAS"));
  test::expectNearCloud(cloud, readScan(dir / "s.LAS"), 0.0005f + 1e-5f);
}

struct CorruptCase {
  const char* name;
  std::function<void(std::string&)> damage;  // applied to a valid LAS 1.4 file of 3 points
  const char* problem;
};

TEST(Las, CorruptHeadersAreErrorsNamingFileAndProblem) {
  const auto setU8 = [](std::size_t at, int v) {
    return [=](std::string& b) { b[at] = static_cast<char>(v); };
  };
  const auto setU16 = [](std::size_t at, std::uint16_t v) {
    return [=](std::string& b) { test::putBytes(b, at, v); };
  };
  const auto setU32 = [](std::size_t at, std::uint32_t v) {
    return [=](std::string& b) { test::putBytes(b, at, v); };
  };
  const auto setU64 = [](std::size_t at, std::uint64_t v) {
    return [=](std::string& b) { test::putBytes(b, at, v); };
  };
  const auto setF64 = [](std::size_t at, double v) {
    return [=](std::string& b) { test::putBytes(b, at, v); };
  };
  const std::vector<CorruptCase> cases = {
      {"empty", [](std::string& b) { b.clear(); }, "empty file"},
      {"signature", setU8(0, 'X'), "no LASF signature"},
      {"short_header", [](std::string& b) { b.resize(200); }, "too few for a LAS header"},
      {"short_14_header", [](std::string& b) { b.resize(300); }, "too few for a LAS 1.4 header"},
      {"version_2", setU8(24, 2), "LAS version 2.4 is not supported"},
      {"version_1_5", setU8(25, 5), "LAS version 1.5 is not supported"},
      {"format_11", setU8(104, 11), "unknown point data record format 11"},
      {"laz", setU8(104, 6 | 0x80), "LAZ-compressed"},
      {"format_6_in_1_2", setU8(25, 2), "needs LAS 1.4"},
      {"short_record", setU16(105, 29), "shorter than the 30 bytes of point data record format 6"},
      {"zero_scale", setF64(139, 0.0), "y scale factor"},
      {"nan_offset", setF64(171, std::nan("")), "z offset is not a finite number"},
      {"header_size", setU16(94, 300), "below the 375 bytes"},
      {"offset_in_header", setU32(96, 100), "lies inside the header"},
      {"count_past_end", setU64(247, 4), "truncated: the header declares 4 points"},
      {"count_overflow", setU64(247, ~0ull / 2), "overflows"},
      {"legacy_disagrees", setU32(107, 2), "legacy point count 2 contradicts the 64-bit point count 3"},
      {"vlr_past_points", setU32(100, 1), "variable length record 1 of 1 does not fit"},
      {"truncated_points", [](std::string& b) { b.resize(b.size() - 1); }, "truncated"},
  };
  test::TempDir dir;
  PointCloud three;
  for (int i = 0; i < 3; ++i) three.add(Vec3f(static_cast<float>(i), 1, 2), 1.0f);
  writeLas(dir / "good.las", three);
  const std::string good = test::readText(dir / "good.las");
  for (const CorruptCase& c : cases) {
    SCOPED_TRACE(c.name);
    std::string bytes = good;
    c.damage(bytes);
    const auto path = dir / (std::string(c.name) + ".las");
    test::writeText(path, bytes);
    test::expectErrorAbout(path, c.problem, [&] { readLas(path); });
  }
}

TEST(Las, VlrLongerThanTheGapIsAnError) {
  test::TempDir dir;
  test::LasSpec spec;
  spec.vlr_payloads = {40};
  std::string bytes = test::lasBytes(spec, {{1, 2, 3, 4}});
  test::putBytes<std::uint16_t>(bytes, 227 + 20, 41);  // one byte into the points
  test::writeText(dir / "v.las", bytes);
  test::expectErrorAbout(dir / "v.las", "past the point data offset", [&] { readLas(dir / "v.las"); });
}

TEST(Las, EveryTruncationIsAnError) {
  test::TempDir dir;
  writeLas(dir / "full.las", test::makeCloud(20, true));
  const std::string full = test::readText(dir / "full.las");
  for (std::size_t length = 0; length < full.size(); length += test::truncationStep(full.size())) {
    const auto path = dir / ("cut" + std::to_string(length) + ".las");
    test::writeText(path, full.substr(0, length));
    EXPECT_THROW(readLas(path), Error) << length;
    EXPECT_THROW(readLasHeader(path), Error) << length;
  }
}

}  // namespace
}  // namespace hba::io
