// `hba info` run as a user would: the built tool on fixture and real datasets.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

test::CommandResult hbaInfo(const std::string& arguments) {
  return test::runCommand(quoted(test::cliPath()) + " info " + arguments);
}

fs::path fixture(const std::string& name) { return test::dataDir() / "datasets" / name; }

void expectContains(const std::string& text, const std::string& piece) {
  EXPECT_NE(text.find(piece), std::string::npos) << "'" << piece << "' not in:\n" << text;
}

TEST(CliInfo, RealFastLioSequenceHas314ScansAndPoses) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1)) GTEST_SKIP() << hku1 << " is absent";
  const test::CommandResult text = hbaInfo(quoted(hku1));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  expectContains(text.output, "scans:       314 (.pcd)");
  expectContains(text.output, "poses:       314 (kitti) from " + (hku1 / "odom_poses.txt").string());
  expectContains(text.output, "duration:");

  // -q keeps the log quiet so the output is the JSON document alone.
  const test::CommandResult json =
      test::runCommand(quoted(test::cliPath()) + " -q info --json " + quoted(hku1));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const nlohmann::json report = nlohmann::json::parse(json.output);
  EXPECT_EQ(report["scan_count"], 314);
  EXPECT_EQ(report["pose_count"], 314);
  EXPECT_EQ(report["layout"], "scans");
  EXPECT_GT(report["trajectory_length_m"].get<double>(), 10.0);
}

TEST(CliInfo, HbaFixtureSummary) {
  const test::CommandResult result = hbaInfo(quoted(fixture("hba_plain")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  expectContains(result.output, "layout:      hba");
  expectContains(result.output, "scans:       11 (.pcd)");
  // The fixture scans hold 2, 3, 4, 2, 3, ... points.
  expectContains(result.output, "points/scan: min 2, median 3, max 4 (11 of 11 scans looked at)");
  expectContains(result.output, "fields:      x y z intensity (PCD ascii)");
  expectContains(result.output, "trajectory:  10.00 m long");
}

TEST(CliInfo, SampleLooksAtFewerScans) {
  const test::CommandResult result = hbaInfo("--sample 2 " + quoted(fixture("hba_plain")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  expectContains(result.output, "(2 of 11 scans looked at)");
}

TEST(CliInfo, KittiFixtureUsesBinSizesAndCalibration) {
  const test::CommandResult result = hbaInfo("--json " + quoted(fixture("kitti_odometry")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  expectContains(result.output, "\"layout\": \"kitti\"");
  expectContains(result.output, "\"max\": 7");  // 112-byte file = 7 points
  expectContains(result.output, "calib.txt");
}

TEST(CliInfo, PosesOverride) {
  const test::CommandResult result =
      hbaInfo(quoted(fixture("fastlio_scans")) + " --poses optimized_poses.txt --format kitti");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  expectContains(result.output, "optimized_poses.txt");
}

TEST(CliInfo, MissingFolderFailsNamingIt) {
  const test::CommandResult result = hbaInfo("/nonexistent/sequence");
  EXPECT_NE(result.exit_code, 0);
  expectContains(result.output, "/nonexistent/sequence: dataset folder not found");
}

TEST(CliInfo, CountMismatchFailsNamingBothFiles) {
  test::TempDir dir;
  fs::create_directories(dir / "Scans");
  for (const char* name : {"000000.pcd", "000001.pcd", "000002.pcd"}) {
    fs::copy_file(fixture("fastlio_scans") / "Scans" / "000000.pcd", dir / "Scans" / name);
  }
  test::writeText(dir / "odom_poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n");
  const test::CommandResult result = hbaInfo(quoted(dir.path()));
  EXPECT_NE(result.exit_code, 0);
  expectContains(result.output, "3 scans in " + (dir / "Scans").string());
  expectContains(result.output, "2 poses in " + (dir / "odom_poses.txt").string());
}

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// hba_plain with the scans `empty` rewritten to hold no points.
fs::path withEmptyScans(const test::TempDir& dir, const std::vector<int>& empty) {
  fs::copy(fixture("hba_plain"), dir.path(), fs::copy_options::recursive);
  for (const int i : empty) {
    test::writeText(dir / "pcd" / (std::to_string(i) + ".pcd"),
                    "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                    "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n");
  }
  return dir.path();
}

TEST(CliInfo, ScansWithNoPointsAreNamedOnce) {
  test::TempDir dir;
  const fs::path data = withEmptyScans(dir, {3, 7});
  const test::CommandResult result = hbaInfo(quoted(data));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* name : {"3.pcd", "7.pcd"}) {
    EXPECT_EQ(occurrences(result.output, (data / "pcd" / name).string() + ": the scan stores no points"), 1u)
        << result.output;
  }
  expectContains(result.output, "points/scan: min 0,");
}

TEST(CliInfo, ManyScansWithNoPointsGiveAFewLinesAndACount) {
  test::TempDir dir;
  const fs::path data = withEmptyScans(dir, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  const test::CommandResult result = hbaInfo(quoted(data));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(occurrences(result.output, ": the scan stores no points"), 3u) << result.output;
  EXPECT_EQ(occurrences(result.output, "more files in this folder have the same problem"), 1u)
      << result.output;
  expectContains(result.output, "11 of the 11 scans looked at store no points");
}

TEST(CliInfo, UnreadableScanFailsNamingIt) {
  const test::CommandResult result = hbaInfo(quoted(fixture("garbage_scans")));
  EXPECT_NE(result.exit_code, 0);
  expectContains(result.output, "000000.pcd");
}

}  // namespace
}  // namespace hba
