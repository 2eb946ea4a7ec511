// The report page's data: thinning to a budget, the encodings the page
// decodes, and the file itself (self-contained, its blocks the sizes the
// script expects). tests/render/report_page_browser.py opens it in Chromium.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>
#include <string>

#include "../eval/synthetic_scans.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/render/report_page.hpp"
#include "page_blocks.hpp"
#include "page_points.hpp"
#include "test_support.hpp"

namespace hba::render {
namespace {

Bytes bytesOf(const std::string& text) { return Bytes(text.begin(), text.end()); }

// RFC 4648, section 10.
TEST(ReportPage, Base64MatchesTheStandardsTestVectors) {
  // Written piece by piece, a long run is the same as at once.
  Bytes long_run(3 * 65536 * 2 + 5);
  for (std::size_t i = 0; i < long_run.size(); ++i) long_run[i] = static_cast<std::uint8_t>(i * 7 + i / 300);
  std::ostringstream pieces;
  writeBase64(pieces, long_run);
  EXPECT_EQ(pieces.str(), base64(long_run));
  EXPECT_EQ(base64(bytesOf("")), "");
  EXPECT_EQ(base64(bytesOf("f")), "Zg==");
  EXPECT_EQ(base64(bytesOf("fo")), "Zm8=");
  EXPECT_EQ(base64(bytesOf("foo")), "Zm9v");
  EXPECT_EQ(base64(bytesOf("foob")), "Zm9vYg==");
  EXPECT_EQ(base64(bytesOf("fooba")), "Zm9vYmE=");
  EXPECT_EQ(base64(bytesOf("foobar")), "Zm9vYmFy");
  EXPECT_EQ(base64(Bytes{0xff, 0xfe, 0x00}), "//4A");
}

// `n` scans of random points in a 20 m cube around each pose.
io::MemoryScanSource randomScans(std::size_t n, std::size_t points, std::vector<Pose>& poses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  std::vector<PointCloud> scans(n);
  poses.clear();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < points; ++k)
      scans[i].add(Vec3f(u(rng), u(rng), u(rng)), static_cast<float>(k % 200));
    poses.push_back(Pose(Quat(Eigen::AngleAxisd(0.1 * static_cast<double>(i), Vec3::UnitZ())),
                         Vec3(0.5 * static_cast<double>(i), 0.0, 0.0)));
  }
  return io::MemoryScanSource(std::move(scans));
}

TEST(ReportPage, MapIsThinnedToTheBudgetInScanOrder) {
  std::vector<Pose> poses;
  const io::MemoryScanSource scans = randomScans(60, 5000, poses);  // 300 000 points
  for (const std::size_t budget : {std::size_t{1000}, std::size_t{20000}, std::size_t{1000000}}) {
    const PagePoints p = samplePagePoints(scans, poses, budget, 0.1);
    EXPECT_LE(p.size(), budget);
    EXPECT_GT(p.size(), budget >= 300000 ? 250000 : budget / 2) << "a budget well used";
    EXPECT_TRUE(std::is_sorted(p.points.begin(), p.points.end(),
                               [](const PagePoint& a, const PagePoint& b) { return a.scan < b.scan; }));
    EXPECT_TRUE(p.has_intensity);
    EXPECT_GE(p.voxel, 0.1);
    if (budget < 300000) {
      EXPECT_GT(p.voxel, 0.1) << "coarser to fit";
    }
    // Thinned to fit: exactly the budget, the share kept said.
    if (p.kept_share < 1.0) {
      EXPECT_EQ(p.size(), budget);
    }
    EXPECT_GT(p.kept_share, 0.5);
  }
}

TEST(ReportPage, ThinningIsTheSameOnAnyThreadCount) {
  std::vector<Pose> poses;
  const io::MemoryScanSource scans = randomScans(80, 3000, poses);
  const auto run = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return samplePagePoints(scans, poses, 30000, 0.1); });
  };
  const PagePoints one = run(1);
  const PagePoints two = run(2);
  const PagePoints five = run(5);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), five.size());
  EXPECT_EQ(std::memcmp(one.points.data(), two.points.data(), one.size() * sizeof(PagePoint)), 0);
  EXPECT_EQ(std::memcmp(one.points.data(), five.points.data(), one.size() * sizeof(PagePoint)), 0);
  EXPECT_EQ(one.voxel, five.voxel);
}

TEST(ReportPage, EachVoxelKeepsItsFirstScansPoint) {
  // Two scans see the same point from poses 1 m apart: the first scan's is kept.
  std::vector<PointCloud> clouds(2);
  clouds[0].add(Vec3f(3.02f, 0.03f, 0.04f));
  clouds[1].add(Vec3f(2.02f, 0.03f, 0.04f));
  const std::vector<Pose> poses = {Pose::identity(), Pose(Quat::Identity(), Vec3(1, 0, 0))};
  const PagePoints p = samplePagePoints(io::MemoryScanSource(clouds), poses, 10, 0.1);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p.points[0].scan, 0u);
  EXPECT_FALSE(p.has_intensity);
}

TEST(ReportPage, PointsRoundTripThroughTheirQuantization) {
  PagePoints p;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-120.0f, 120.0f);
  for (int i = 0; i < 1000; ++i) p.points.push_back({0, 0.0f, Vec3f(u(rng), u(rng), u(rng))});
  const QuantizedPoints q = quantizePoints(p);
  ASSERT_EQ(q.xyz.size(), 6 * p.size());
  EXPECT_LT(q.step, 120.0 / 32767.0 * 1.001);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      std::int16_t v = 0;
      std::memcpy(&v, &q.xyz[6 * i + 2 * static_cast<std::size_t>(a)], 2);
      EXPECT_NEAR(v * q.step, p.points[i].local(a), 0.5 * q.step + 1e-6);
    }
  }
}

TEST(ReportPage, PosesAreFloatRowsRelativeToTheOrigin) {
  const Pose pose(Quat(Eigen::AngleAxisd(0.5, Vec3(1, 2, 3).normalized())), Vec3(500010.25, 4200003.5, 12.0));
  const Vec3 origin(500000.0, 4200000.0, 10.0);
  const Bytes rows = poseRows({pose}, origin);
  ASSERT_EQ(rows.size(), 48u);
  float f[12];
  std::memcpy(f, rows.data(), 48);
  const Mat3 R = pose.R();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[3 * r + c], R(r, c), 1e-6);
  EXPECT_NEAR(f[9], 10.25, 1e-5);
  EXPECT_NEAR(f[10], 3.5, 1e-5);
  EXPECT_NEAR(f[11], 2.0, 1e-5);
}

// A wall seen by two scans: 5 cm apart with the `before` poses, one with `after`.
TEST(ReportPage, ThicknessChangeMarksTheWallThatGotCrisper) {
  PagePoints p;
  for (std::uint32_t scan = 0; scan < 2; ++scan) {
    for (double y = 0.0; y < 4.0; y += 0.1) {
      for (double z = 0.0; z < 2.0; z += 0.1) {
        p.points.push_back({scan, 0.0f, Vec3f(4.5f, static_cast<float>(y), static_cast<float>(z))});
      }
    }
  }
  const std::vector<Pose> after = {Pose::identity(), Pose::identity()};
  const std::vector<Pose> before = {Pose::identity(), Pose(Quat::Identity(), Vec3(0.05, 0, 0))};
  const Bytes codes = thicknessChangeCodes(p, before, after, 1.0);
  ASSERT_EQ(codes.size(), p.size());
  std::size_t thinner = 0, measured = 0;
  for (const std::uint8_t c : codes) {
    measured += c != 0;
    // 2.5 cm thick before (the two walls' spread), flat after: 25 mm in steps of 0.2 mm.
    thinner += c == 128 + 125;
  }
  EXPECT_GT(measured, p.size() * 9 / 10);
  EXPECT_EQ(thinner, measured);
  const Bytes same = thicknessChangeCodes(p, after, after, 1.0);
  for (const std::uint8_t c : same) EXPECT_TRUE(c == 0 || c == 128);
}

std::string blockText(const std::string& page, const std::string& id) {
  const std::string open = "<script type=\"application/octet-stream\" id=\"hba-" + id + "\">";
  const std::size_t at = page.find(open);
  if (at == std::string::npos) return {};
  const std::size_t start = at + open.size();
  return page.substr(start, page.find("</script>", start) - start);
}

std::size_t decodedSize(const std::string& b64) {
  const std::size_t pad =
      b64.empty() ? 0 : static_cast<std::size_t>(std::count(b64.end() - 2, b64.end(), '='));
  return b64.size() / 4 * 3 - pad;
}

TEST(ReportPage, PageIsSelfContainedAndCarriesEveryBlock) {
  test::TempDir dir;
  const std::vector<Pose> gt = test::syntheticPoses();
  std::vector<Pose> before = gt;
  for (Pose& p : before) p.t += Vec3(0.02, -0.01, 0.0);
  const io::MemoryScanSource scans(test::syntheticScans(gt));
  ReportPageInput input;
  input.title = "wall </script><b>";
  input.before = before;
  input.after = gt;
  input.ground_truth = gt;
  input.report = {{"warnings", {"a </script> inside a string"}}, {"seconds", {{"total", 1.5}}}};
  const ReportPageFigures figures = writeReportPage(scans, input, dir / "report.html");
  const std::string page = test::readText(dir / "report.html");
  EXPECT_EQ(figures.bytes, page.size());
  EXPECT_TRUE(isReportPage(dir / "report.html"));
  // No resource from the network, and no text that ends a script early.
  EXPECT_FALSE(std::regex_search(page, std::regex(R"((src|href)\s*=\s*["']?(https?:)?//)")));
  EXPECT_EQ(page.find("wall </script><b>"), std::string::npos);
  EXPECT_NE(page.find("wall &lt;/script&gt;&lt;b&gt;"), std::string::npos);

  const std::string open = "<script type=\"application/json\" id=\"hba-data\">";
  const std::size_t start = page.find(open) + open.size();
  const nlohmann::json data =
      nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
  EXPECT_EQ(data.at("frames"), gt.size());
  EXPECT_EQ(data.at("points"), figures.points);
  EXPECT_EQ(data.at("report").at("warnings").at(0), "a </script> inside a string");
  const std::size_t n = figures.points;
  EXPECT_GT(n, 1000u);
  EXPECT_EQ(decodedSize(blockText(page, "xyz")), 6 * n);
  EXPECT_EQ(decodedSize(blockText(page, "change")), n);
  EXPECT_EQ(decodedSize(blockText(page, "per-scan")), 4 * gt.size());
  for (const char* id : {"pose-input", "pose-optimized", "pose-ground-truth"})
    EXPECT_EQ(decodedSize(blockText(page, id)), 48 * gt.size()) << id;
  EXPECT_EQ(decodedSize(blockText(page, "intensity")), data.at("has_intensity").get<bool>() ? n : 0);
}

TEST(ReportPage, HugeMapStaysWithinItsBudgetAndBadInputIsRefused) {
  test::TempDir dir;
  std::vector<Pose> poses;
  const io::MemoryScanSource scans = randomScans(40, 20000, poses);  // 800 000 points
  ReportPageInput input;
  input.before = poses;
  input.after = poses;
  ReportPageSettings settings;
  settings.point_budget = 5000;
  const ReportPageFigures figures = writeReportPage(scans, input, dir / "page.html", settings);
  EXPECT_LE(figures.points, 5000u);
  EXPECT_LT(figures.bytes, 200000u);

  input.after.pop_back();
  try {
    writeReportPage(scans, input, dir / "bad.html", settings);
    FAIL() << "a pose short";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("39 poses for 40 scans"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.html"));
  test::writeText(dir / "other.html", "<html>mine</html>");
  EXPECT_FALSE(isReportPage(dir / "other.html"));
}

}  // namespace
}  // namespace hba::render
