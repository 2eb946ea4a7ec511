// The same input and settings give byte-identical outputs whatever the
// thread count: parallel work must not change the order of floating-point
// sums, nor may the thread count change what is computed.
#include <gtest/gtest.h>

#include "cli_runs.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

void writeRoomSequence(const fs::path& dir, std::size_t scans) {
  const std::vector<Pose> truth = test::straightPath(scans);
  test::writeSceneDataset(dir, test::roomScene(1500), truth, test::perturbed(truth, 0.05, 0.5, 11));
}

TEST(Determinism, OneAndTwoThreadsWriteIdenticalPoses) {
  TempDir tmp;
  writeRoomSequence(tmp / "data", 30);  // 30 scans: two pyramid layers, five windows
  // --layers fixed: the automatic layer count follows the thread count (see below).
  const test::CommandResult one = test::runOptimize(tmp / "data", tmp / "j1", "--layers 2", 1);
  const test::CommandResult two = test::runOptimize(tmp / "data", tmp / "j2", "--layers 2", 2);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  ASSERT_EQ(two.exit_code, 0) << two.output;
  for (const char* name : {"pose.json", "poses_kitti.txt", "poses_tum.txt"}) {
    const std::string a = test::readText(tmp / "j1" / name);
    ASSERT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, test::readText(tmp / "j2" / name)) << name << " differs between -j 1 and -j 2";
  }
}

TEST(Determinism, RepeatedRunsWriteIdenticalPoses) {
  TempDir tmp;
  writeRoomSequence(tmp / "data", 30);
  const test::CommandResult first = test::runOptimize(tmp / "data", tmp / "a", "", 2);
  const test::CommandResult second = test::runOptimize(tmp / "data", tmp / "b", "", 2);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(test::readText(tmp / "a" / "pose.json"), test::readText(tmp / "b" / "pose.json"));
}

// -j limits the threads hba optimize uses, and says so; the pyramid does not
// depend on the thread count (the layer rule uses the paper's fixed n = 8).
TEST(Determinism, ThreadFlagIsTheThreadCountUsed) {
  TempDir tmp;
  writeRoomSequence(tmp / "data", 12);
  const test::CommandResult one = test::runOptimize(tmp / "data", tmp / "j1", "", 1);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(one.output.find("threads: 1"), std::string::npos) << one.output;
}

}  // namespace
}  // namespace hba
