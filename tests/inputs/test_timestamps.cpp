// Timestamps flow from the input to every output: the simulator's times.txt,
// TUM output that pairs with ground truth by time, `hba eval` refusing files
// whose times do not agree, and scans named by time.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runs.hpp"
#include "hba/io/pose_file.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

nlohmann::json evalJson(const fs::path& gt, const fs::path& est, const fs::path& json) {
  const test::CommandResult result = test::runHba("-q eval --gt " + test::quoted(gt) + " --est " +
                                                  test::quoted(est) + " --json " + test::quoted(json));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return nlohmann::json::parse(test::readText(json));
}

// gt.txt, pose.json (by index) and poses_tum.txt (by time) tell one story.
TEST(Timestamps, SimulatorTumOutputPairsWithGroundTruthByTime) {
  test::TempDir dir;
  ASSERT_EQ(test::runHba("-q simulate --frames 40 --seed 6 -o " + test::quoted(dir / "sim")).exit_code, 0);
  ASSERT_EQ(test::runOptimize(dir / "sim", dir / "out", "--no-render").exit_code, 0);
  const nlohmann::json by_index = evalJson(dir / "sim" / "gt.txt", dir / "out" / "pose.json", dir / "a.json");
  const nlohmann::json by_time =
      evalJson(dir / "sim" / "gt.txt", dir / "out" / "poses_tum.txt", dir / "b.json");
  EXPECT_EQ(by_index.at("association"), "index");
  EXPECT_EQ(by_time.at("association"), "time");
  EXPECT_EQ(by_time.at("matched"), 40);
  EXPECT_DOUBLE_EQ(by_time.at("ate").at("translation_m").at("rmse").get<double>(),
                   by_index.at("ate").at("translation_m").at("rmse").get<double>());
  const Trajectory tum = io::readPoses(dir / "out" / "poses_tum.txt");
  EXPECT_DOUBLE_EQ(tum.stamps[39], 3.9);
}

// Without stamps the TUM output carries scan indices; evaluating it by time
// against real stamps must fail and say why, not score 10 % of the poses.
TEST(Timestamps, EvalRefusesTimesThatDoNotAgree) {
  test::TempDir dir;
  ASSERT_EQ(
      test::runHba("-q simulate --frames 40 --seed 6 --poses-only -o " + test::quoted(dir / "sim")).exit_code,
      0);
  Trajectory indexed = io::readPoses(dir / "sim" / "gt.txt");
  for (std::size_t i = 0; i < indexed.size(); ++i) indexed.stamps[i] = static_cast<double>(i);
  io::writePoses(dir / "indexed.txt", indexed, io::PoseFormat::Tum);
  const std::string args =
      "eval --gt " + test::quoted(dir / "sim" / "gt.txt") + " --est " + test::quoted(dir / "indexed.txt");
  const test::CommandResult refused = test::runHba(args);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("only 4 of 40 estimated poses"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("--assoc index"), std::string::npos) << refused.output;
  EXPECT_EQ(test::runHba(args + " --assoc index").exit_code, 0);
  EXPECT_EQ(test::runHba(args + " --min-matched 0.05").exit_code, 0);
}

// A copy of hku1 with scans named by time (bag-to-PCD style) and a TUM
// trajectory optimizes to the same poses as the original.
TEST(Timestamps, Hku1WithScansNamedByTimeGivesTheSamePoses) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  const fs::path copy = dir / "named";
  fs::create_directories(copy / "pcd");
  const std::vector<double> stamps = io::readTimes(data / "times.txt");
  Trajectory trajectory = io::readPoses(data / "odom_poses.txt");
  trajectory.stamps = stamps;
  io::writePoses(copy / "trajectory.tum", trajectory, io::PoseFormat::Tum);
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const auto ns = static_cast<long long>(std::llround(stamps[i] * 1e9));
    char name[64];
    std::snprintf(name, sizeof(name), "%lld.%09lld.pcd", ns / 1000000000LL, ns % 1000000000LL);
    char original[32];
    std::snprintf(original, sizeof(original), "%06zu.pcd", i);
    fs::create_symlink(data / "Scans" / original, copy / "pcd" / name);
  }
  ASSERT_EQ(test::runOptimize(data, dir / "a", "--no-render", 2).exit_code, 0);
  const test::CommandResult named = test::runOptimize(copy, dir / "b", "--no-render", 2);
  ASSERT_EQ(named.exit_code, 0) << named.output;
  EXPECT_LT(
      test::largestTranslation(test::readOptimizedPoses(dir / "a"), test::readOptimizedPoses(dir / "b")),
      1e-9);
  EXPECT_EQ(io::readPoses(dir / "b" / "poses_tum.txt").stamps, trajectory.stamps);
}

}  // namespace
}  // namespace hba

namespace hba {
namespace {

// Errors of 100 m and more keep a space between the table's columns.
TEST(EvalTable, LargeErrorsStaySeparated) {
  test::TempDir dir;
  Trajectory gt, est;
  for (int i = 0; i < 5; ++i) {
    gt.poses.push_back(Pose(Quat::Identity(), Vec3(i, 0, 0)));
    est.poses.push_back(Pose(Quat::Identity(), Vec3(i + 1234.5, 0, 0)));
  }
  io::writePoses(dir / "gt.txt", gt, io::PoseFormat::Kitti);
  io::writePoses(dir / "est.txt", est, io::PoseFormat::Kitti);
  const test::CommandResult run = test::runHba("-q eval --align none --gt " + test::quoted(dir / "gt.txt") +
                                               " --est " + test::quoted(dir / "est.txt"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(
                "ATE trans m    1234.500000 1234.500000 1234.500000    0.000000 1234.500000 1234.500000"),
            std::string::npos)
      << run.output;
}

// The default single pass is not reported as a failure to converge.
TEST(ReportJson, SaysWhyTheOuterIterationsStopped) {
  test::TempDir dir;
  ASSERT_EQ(test::runHba("-q simulate --frames 30 --seed 2 -o " + test::quoted(dir / "sim")).exit_code, 0);
  ASSERT_EQ(test::runOptimize(dir / "sim", dir / "out", "--no-render").exit_code, 0);
  const nlohmann::json report = nlohmann::json::parse(test::readText(dir / "out" / "report.json"));
  EXPECT_FALSE(report.contains("converged"));
  EXPECT_EQ(report.at("outer_iterations").at("run"), 1);
  EXPECT_EQ(report.at("outer_iterations").at("stopped"), "iteration limit");
  EXPECT_EQ(report.at("input").at("stamps"), "times file");
  EXPECT_TRUE(report.at("convention_check").contains("as_given"));
}

// Negative voxel sizes are refused with a readable message.
TEST(MapCli, NegativeVoxelIsRefused) {
  test::TempDir dir;
  ASSERT_EQ(test::runHba("-q simulate --frames 5 --seed 2 -o " + test::quoted(dir / "sim")).exit_code, 0);
  const test::CommandResult run =
      test::runHba("map " + test::quoted(dir / "sim") + " -o " + test::quoted(dir / "m.pcd") + " --voxel -1");
  EXPECT_EQ(run.exit_code, 2);  // usage: a bad value
  EXPECT_NE(run.output.find("--voxel: must be 0 (keep every point) or [0.001, 100] m, got -1"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(dir / "m.pcd"));
}

}  // namespace
}  // namespace hba
