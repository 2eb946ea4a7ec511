// `hba simulate` run as a user would: the dataset it writes is readable by
// `hba info`, the thread count never changes a byte, --poses-only writes
// the pose files of a full run, and --sessions writes several in one world.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace {
namespace fs = std::filesystem;
using hba::test::cliPath;
using hba::test::runCommand;

std::string simulate(const std::string& extra) {
  return cliPath().string() + " " + extra + " simulate --frames 25 --sensor livox --seed 4";
}

TEST(CliSimulate, WritesADatasetThatInfoReads) {
  hba::test::TempDir dir;
  const auto made = runCommand(simulate("") + " -o " + (dir / "seq").string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_NE(made.output.find("25 frames"), std::string::npos) << made.output;
  const auto info = runCommand(cliPath().string() + " info " + (dir / "seq").string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("25"), std::string::npos) << info.output;
}

TEST(CliSimulate, OneAndTwoThreadsWriteTheSameBytes) {
  hba::test::TempDir dir;
  ASSERT_EQ(runCommand(simulate("-j 1") + " -o " + (dir / "a").string()).exit_code, 0);
  ASSERT_EQ(runCommand(simulate("-j 2") + " -o " + (dir / "b").string()).exit_code, 0);
  const auto a = hba::test::fileContents(dir / "a");
  EXPECT_EQ(a.size(), 29u);  // 25 scans, pose.json, gt.txt, times.txt, sim.yaml
  EXPECT_TRUE(a == hba::test::fileContents(dir / "b"));
}

TEST(CliSimulate, PosesOnlyWritesAFullRunsPoseFilesWithoutScans) {
  hba::test::TempDir dir;
  const std::string flags = simulate("") + " --loop-closed -o ";
  ASSERT_EQ(runCommand(flags + (dir / "full").string()).exit_code, 0);
  const auto made = runCommand(flags + (dir / "poses").string() + " --poses-only");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_FALSE(fs::exists(dir / "poses" / "pcd"));
  const auto full = hba::test::fileContents(dir / "full");
  const auto poses = hba::test::fileContents(dir / "poses");
  ASSERT_EQ(poses.size(), 4u);
  for (const char* name : {"pose.json", "gt.txt", "times.txt", "sim.yaml"}) {
    EXPECT_EQ(poses.at(name), full.at(name)) << name;
  }
}

TEST(CliSimulate, RefusesToOverwriteAndRejectsBadFlags) {
  hba::test::TempDir dir;
  fs::create_directory(dir / "full");
  hba::test::writeText(dir / "full" / "keep.txt", "x");
  const auto refused = runCommand(simulate("") + " -o " + (dir / "full").string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
  EXPECT_TRUE(fs::exists(dir / "full" / "keep.txt"));

  const auto bad_sensor = runCommand(simulate("") + " --sensor hdl128 -o " + (dir / "x").string());
  EXPECT_NE(bad_sensor.exit_code, 0);
  const auto bad_path = runCommand(simulate("") + " --trajectory /no/such/file -o " + (dir / "y").string());
  EXPECT_NE(bad_path.exit_code, 0);
  EXPECT_NE(bad_path.output.find("/no/such/file"), std::string::npos) << bad_path.output;
  const auto bad_noise = runCommand(simulate("") + " --noise -1 -o " + (dir / "z").string());
  EXPECT_NE(bad_noise.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "x") || fs::exists(dir / "y") || fs::exists(dir / "z"));
}

TEST(CliSimulate, OneSessionWritesExactlyTheSingleDataset) {
  hba::test::TempDir dir;
  ASSERT_EQ(runCommand(simulate("") + " -o " + (dir / "plain").string()).exit_code, 0);
  const auto one = runCommand(simulate("") + " --sessions 1 --session-shift 9 -o " + (dir / "one").string());
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_TRUE(hba::test::fileContents(dir / "plain") == hba::test::fileContents(dir / "one"));
}

TEST(CliSimulate, SessionsWriteAFolderEachWithTheSameBytesForAnyThreadCount) {
  hba::test::TempDir dir;
  const std::string flags = " --sessions 3 --session-shift 2 --session-reverse --session-frames 10 -o ";
  const auto made = runCommand(simulate("-j 1") + flags + (dir / "a").string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_NE(made.output.find("session-1: 10 frames"), std::string::npos) << made.output;
  ASSERT_EQ(runCommand(simulate("-j 2") + flags + (dir / "b").string()).exit_code, 0);
  const auto a = hba::test::fileContents(dir / "a");
  // 3 x 10 scans; pose.json, gt.txt, gt_world.txt, session_frame.txt, times.txt, sim.yaml each.
  EXPECT_EQ(a.size(), 30u + 3u * 6u);
  EXPECT_EQ(a.count("session-0/pcd/000010.pcd"), 0u);
  EXPECT_EQ(a.count("session-2/pcd/000009.pcd"), 1u);
  EXPECT_TRUE(a == hba::test::fileContents(dir / "b"));
  // Each session is a dataset `hba info` reads.
  const auto info = runCommand(cliPath().string() + " info " + (dir / "a" / "session-1").string());
  EXPECT_EQ(info.exit_code, 0) << info.output;
}

TEST(CliSimulate, RejectsBadSessionSettingsByName) {
  hba::test::TempDir dir;
  const auto none = runCommand(simulate("") + " --sessions 0 -o " + (dir / "x").string());
  EXPECT_NE(none.exit_code, 0);
  EXPECT_NE(none.output.find("--sessions"), std::string::npos) << none.output;
  const auto backwards =
      runCommand(simulate("") + " --sessions 2 --session-shift=-5 -o " + (dir / "y").string());
  EXPECT_NE(backwards.exit_code, 0);
  EXPECT_NE(backwards.output.find("--session-shift"), std::string::npos) << backwards.output;
  EXPECT_FALSE(fs::exists(dir / "x") || fs::exists(dir / "y"));
}

}  // namespace
