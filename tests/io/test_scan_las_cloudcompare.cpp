// An independent LAS implementation reads what hba writes and writes what
// hba reads: CloudCompare's command line, run headless under xvfb-run. The
// tests skip where CloudCompare, xvfb-run, or CloudCompare's LAS support
// (a build option) is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "hba/io/las.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

// CloudCompare keeps points as floats shifted near the origin: micrometres.
constexpr double kCloudCompareSlack = 1e-5;
const Vec3 kUtm(500000.0, 4500000.0, 100.0);

std::string quotedPath(const fs::path& path) { return "'" + path.string() + "'"; }

test::CommandResult runCloudCompare(const std::string& arguments) {
  return test::runCommand("xvfb-run -a CloudCompare -SILENT -AUTO_SAVE OFF " + arguments);
}

std::vector<Vec3> surveyPoints(std::size_t n) {
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i);
    points.push_back(kUtm + Vec3(30.0 * std::sin(0.21 * t), 0.125 * t, 2.0 * std::cos(0.5 * t)));
  }
  return points;
}

void writeAscii(const fs::path& path, const std::vector<Vec3>& points) {
  std::ofstream out(path);
  out.precision(12);
  for (const Vec3& p : points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
}

std::vector<Vec3> readAscii(const fs::path& path) {
  std::vector<Vec3> points;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    Vec3 p;
    if (words >> p.x() >> p.y() >> p.z()) points.push_back(p);
  }
  return points;
}

// Why the CloudCompare tests cannot run here, or empty when they can.
std::string cloudCompareMissing(const test::TempDir& dir) {
  if (!test::toolInstalled("CloudCompare")) return "CloudCompare not installed";
  if (!test::toolInstalled("xvfb-run")) return "xvfb-run not installed (CloudCompare needs a display)";
  writeAscii(dir / "probe.xyz", surveyPoints(3));
  runCloudCompare("-O -GLOBAL_SHIFT AUTO " + quotedPath(dir / "probe.xyz") +
                  " -C_EXPORT_FMT LAS -SAVE_CLOUDS FILE " + quotedPath(dir / "probe.las"));
  if (!fs::exists(dir / "probe.las"))
    return "this CloudCompare build has no LAS support (no libLAS/PDAL plugin)";
  return {};
}

TEST(LasCloudCompare, CloudCompareReadsTheLasHbaWrites) {
  test::TempDir dir;
  if (const std::string missing = cloudCompareMissing(dir); !missing.empty()) GTEST_SKIP() << missing;
  PointCloud cloud;
  cloud.origin = kUtm;
  for (const Vec3& p : surveyPoints(400)) cloud.add((p - kUtm).cast<float>(), 1.0f);
  writeLas(dir / "hba.las", cloud);
  const test::CommandResult run = runCloudCompare("-O -GLOBAL_SHIFT AUTO " + quotedPath(dir / "hba.las") +
                                                  " -C_EXPORT_FMT ASC -PREC 6 -SEP SPACE -SAVE_CLOUDS FILE " +
                                                  quotedPath(dir / "cc.txt"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<Vec3> back = readAscii(dir / "cc.txt");
  ASSERT_EQ(back.size(), cloud.size()) << run.output;
  for (std::size_t i = 0; i < back.size(); ++i) {
    ASSERT_LE((back[i] - cloud.world(i)).cwiseAbs().maxCoeff(), 0.0005 + kCloudCompareSlack) << "point " << i;
  }
}

TEST(LasCloudCompare, HbaReadsTheLasCloudCompareWrites) {
  test::TempDir dir;
  if (const std::string missing = cloudCompareMissing(dir); !missing.empty()) GTEST_SKIP() << missing;
  const std::vector<Vec3> points = surveyPoints(400);
  writeAscii(dir / "cloud.xyz", points);
  const test::CommandResult run =
      runCloudCompare("-O -GLOBAL_SHIFT AUTO " + quotedPath(dir / "cloud.xyz") +
                      " -C_EXPORT_FMT LAS -SAVE_CLOUDS FILE " + quotedPath(dir / "cc.las"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const PointCloud back = readLas(dir / "cc.las");
  ASSERT_EQ(back.size(), points.size()) << run.output;
  for (std::size_t i = 0; i < back.size(); ++i) {
    ASSERT_LE((back.world(i) - points[i]).cwiseAbs().maxCoeff(), 0.001 + kCloudCompareSlack) << "point " << i;
  }
}

}  // namespace
}  // namespace hba::io
