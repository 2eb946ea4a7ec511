// Degenerate datasets through the built `hba optimize`, as a user would run
// it: each ends with a clear message or a sensible result, never NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cli_runs.hpp"
#include "hba/io/pcd.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

void expectContains(const std::string& text, const std::string& piece) {
  EXPECT_NE(text.find(piece), std::string::npos) << "'" << piece << "' not in:\n" << text;
}

// The "[error] ..." lines of a run's log (what the user is told went wrong).
std::string errorLines(const std::string& output) {
  std::string errors;
  std::size_t start = 0;
  while ((start = output.find("[error]", start)) != std::string::npos) {
    const std::size_t end = output.find('\n', start);
    errors += output.substr(start, end - start) + "\n";
    start = end;
  }
  return errors;
}

// A well-constrained room seen from `count` slightly wrong poses.
void writeRoom(const fs::path& dir, std::size_t count) {
  const std::vector<Pose> truth = test::straightPath(count);
  test::writeSceneDataset(dir, test::roomScene(), truth, test::perturbed(truth, 0.03, 0.3, 7));
}

// Rewrites every `step`-th point of a scan with `bad(i)`: a corrupt scan
// as a broken driver or converter would write it.
template <typename BadPoint>
void corruptPoints(const fs::path& scan, std::size_t step, BadPoint bad,
                   io::PcdEncoding encoding = io::PcdEncoding::Binary) {
  PointCloud cloud = io::readPcd(scan);
  for (std::size_t i = 0; i < cloud.size(); i += step) cloud.points[i] = bad(i);
  io::writePcd(scan, cloud, encoding);
}

TEST(DegenerateData, RoomBaselineImprovesAndStaysFinite) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
}

TEST(DegenerateData, EmptyScanIsReportedOrSkipped) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  io::writePcd(tmp / "data" / "pcd" / "5.pcd", PointCloud{});
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  // A warning names the scan once, however often the run reads it.
  const std::string warning = (tmp / "data" / "pcd" / "5.pcd").string() + ": the scan has no points";
  EXPECT_NE(run.output.find(warning), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(warning), run.output.rfind(warning)) << run.output;
  if (run.exit_code != 0) {
    expectContains(errorLines(run.output), "5.pcd");  // the message names the empty scan
    EXPECT_FALSE(fs::exists(tmp / "out" / "pose.json"));
    return;
  }
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
  // The scan-less frame follows its neighbours: no wild jump.
  const std::vector<Pose> initial = test::perturbed(test::straightPath(12), 0.03, 0.3, 7);
  const std::vector<Pose> result = test::readOptimizedPoses(tmp / "out");
  ASSERT_EQ(result.size(), 12u);
  EXPECT_LT((result[5].t - initial[5].t).norm(), 0.2);
}

TEST(DegenerateData, AllScansEmptyIsAnErrorOrPosesUnchanged) {
  TempDir tmp;
  const std::vector<Pose> poses = test::straightPath(12);
  test::writeSceneDataset(tmp / "data", test::roomScene(0), poses, poses);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  // Twelve empty scans in one folder: three named, then one line for the rest.
  std::size_t named = 0;
  for (std::size_t at = run.output.find(": the scan has no points"); at != std::string::npos;
       at = run.output.find(": the scan has no points", at + 1)) {
    ++named;
  }
  EXPECT_EQ(named, 3u) << run.output;
  expectContains(run.output, "more files in this folder have the same problem (scans with no points)");
  if (run.exit_code == 0) {
    test::expectFiniteOptimizeOutputs(tmp / "out", 12);
    EXPECT_LT(test::largestTranslation(test::readOptimizedPoses(tmp / "out"), poses), 1e-6);
  } else {
    EXPECT_FALSE(errorLines(run.output).empty()) << run.output;
  }
}

TEST(DegenerateData, NanAndInfPointsAreDroppedNotPropagated) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  // Rewrite two scans with non-finite points mixed in (the writer keeps them).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const char* name : {"2.pcd", "7.pcd"}) {
    corruptPoints(
        tmp / "data" / "pcd" / name, 10,
        [&](std::size_t i) { return (i % 20 == 0) ? Vec3f(nan, 0, 1) : Vec3f(inf, -inf, 0); },
        io::PcdEncoding::BinaryCompressed);
  }
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
}

// Finite but absurd coordinates (a corrupt scan): far beyond any voxel index
// a 64-bit integer can hold. Under the sanitizer build this also proves the
// voxel hashing does no undefined float-to-integer conversion.
TEST(DegenerateData, FarAwayPointsDoNotBreakTheRun) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  corruptPoints(tmp / "data" / "pcd" / "4.pcd", 50, [](std::size_t) { return Vec3f(1e30f, -3e38f, 1e25f); });
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
}

// One scan has nothing to be aligned with: either a clear refusal or the pose
// unchanged (hba returns it unchanged with a warning).
TEST(DegenerateData, OneScanKeepsItsPoseOrSaysWhy) {
  TempDir tmp;
  writeRoom(tmp / "data", 1);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  if (run.exit_code != 0) {
    expectContains(errorLines(run.output), "scan");  // e.g. "needs at least 2 scans"
    return;
  }
  test::expectFiniteOptimizeOutputs(tmp / "out", 1);
  const std::vector<Pose> initial = test::perturbed(test::straightPath(1), 0.03, 0.3, 7);
  EXPECT_LT(test::largestTranslation(test::readOptimizedPoses(tmp / "out"), initial), 1e-6);
}

TEST(DegenerateData, FewerScansThanAWindow) {
  TempDir tmp;
  writeRoom(tmp / "data", 4);  // the default window is 10
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 4);
}

TEST(DegenerateData, IdenticalPosesAndScans) {
  TempDir tmp;
  // A vehicle standing still: every pose and every scan the same.
  const std::vector<Pose> still(12, test::straightPath(1).front());
  test::writeSceneDataset(tmp / "data", test::roomScene(), still, still);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
  const std::vector<Pose> result = test::readOptimizedPoses(tmp / "out");
  EXPECT_LT(test::largestTranslation(result, still), 0.05);
  EXPECT_LT(test::largestRotationDeg(result, still), 0.5);
}

TEST(DegenerateData, NonUnitQuaternionsAreRenormalized) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  // The same rotations written with quaternions scaled by 3 (and one by -1).
  const std::vector<Pose> initial = test::perturbed(test::straightPath(12), 0.03, 0.3, 7);
  std::string text;
  for (std::size_t i = 0; i < initial.size(); ++i) {
    const Pose& p = initial[i];
    const double scale = i == 3 ? -1.0 : 3.0;
    char line[256];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.t.x(), p.t.y(), p.t.z(),
                  scale * p.q.w(), scale * p.q.x(), scale * p.q.y(), scale * p.q.z());
    text += line;
  }
  fs::create_directories(tmp / "scaled");
  fs::copy(tmp / "data" / "pcd", tmp / "scaled" / "pcd");
  test::writeText(tmp / "scaled" / "pose.json", text);

  const test::CommandResult unit = test::runOptimize(tmp / "data", tmp / "out_unit");
  const test::CommandResult scaled = test::runOptimize(tmp / "scaled", tmp / "out_scaled");
  ASSERT_EQ(unit.exit_code, 0) << unit.output;
  ASSERT_EQ(scaled.exit_code, 0) << scaled.output;
  test::expectFiniteOptimizeOutputs(tmp / "out_scaled", 12);
  const std::vector<Pose> a = test::readOptimizedPoses(tmp / "out_unit");
  const std::vector<Pose> b = test::readOptimizedPoses(tmp / "out_scaled");
  EXPECT_LT(test::largestTranslation(a, b), 1e-6);
  EXPECT_LT(test::largestRotationDeg(a, b), 1e-6);
}

TEST(DegenerateData, ZeroQuaternionIsAnErrorNamingTheLine) {
  TempDir tmp;
  writeRoom(tmp / "data", 12);
  std::string poses = test::readText(tmp / "data" / "pose.json");
  // Replace the third line's quaternion with zeros.
  std::size_t start = 0;
  for (int line = 0; line < 2; ++line) start = poses.find('\n', start) + 1;
  const std::size_t end = poses.find('\n', start);
  poses.replace(start, end - start, "0.8 0 1.5 0 0 0 0");
  test::writeText(tmp / "data" / "pose.json", poses);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  EXPECT_NE(run.exit_code, 0) << run.output;
  expectContains(run.output, "pose.json: line 3");
  EXPECT_FALSE(fs::exists(tmp / "out" / "pose.json"));
}

// Sparse noise: no voxel holds enough points for a plane, so nothing is
// optimized and the tool says so.
TEST(DegenerateData, FeaturelessSceneLeavesPosesUnchangedWithAWarning) {
  TempDir tmp;
  const std::vector<Pose> truth = test::straightPath(12);
  const std::vector<Pose> initial = test::perturbed(truth, 0.03, 0.3, 7);
  test::writeSceneDataset(tmp / "data", test::featurelessScene(300), truth, initial);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
  expectContains(run.output, "[warning]");
  const std::vector<Pose> result = test::readOptimizedPoses(tmp / "out");
  EXPECT_LT(test::largestTranslation(result, initial), 1e-6) << run.output;
  EXPECT_LT(test::largestRotationDeg(result, initial), 1e-6);
}

// Dense noise (2000 random points a scan, independently drawn: nothing
// consistent between scans): chance "planes" among few points must not pass
// the plane test and drag the poses.
TEST(DegenerateData, DenseFeaturelessSceneIsNotWarped) {
  TempDir tmp;
  const std::vector<Pose> truth = test::straightPath(12);
  const std::vector<Pose> initial = test::perturbed(truth, 0.03, 0.3, 7);
  test::writeSceneDataset(tmp / "data", test::featurelessScene(2000), truth, initial);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
  const std::vector<Pose> result = test::readOptimizedPoses(tmp / "out");
  EXPECT_LT(test::largestTranslation(result, initial), 0.1) << run.output;
  EXPECT_LT(test::largestRotationDeg(result, initial), 1.0);
}

TEST(DegenerateData, CorridorDoesNotWanderAlongItsAxis) {
  TempDir tmp;
  const std::vector<Pose> truth = test::straightPath(12);
  const std::vector<Pose> initial = test::perturbed(truth, 0.03, 0.3, 7);
  test::writeSceneDataset(tmp / "data", test::corridorScene(), truth, initial);
  const test::CommandResult run = test::runOptimize(tmp / "data", tmp / "out");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  test::expectFiniteOptimizeOutputs(tmp / "out", 12);
  const std::vector<Pose> result = test::readOptimizedPoses(tmp / "out");
  // Along the corridor nothing is observed: the update there must stay small
  // (a weak weight), not run off; across it the walls pull the poses in.
  double largest_along = 0.0;
  for (std::size_t i = 0; i < result.size(); ++i) {
    largest_along = std::max(largest_along, std::abs(result[i].t.x() - initial[i].t.x()));
  }
  EXPECT_LT(largest_along, 0.2) << run.output;
  EXPECT_LT(test::largestTranslation(result, truth), 0.3) << run.output;
}

}  // namespace
}  // namespace hba
