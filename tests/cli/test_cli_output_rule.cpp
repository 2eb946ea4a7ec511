// One output rule: a non-empty output folder is refused unless --force,
// which replaces it whole; a second run into a folder in use is refused;
// Ctrl-C leaves nothing behind (no folder, no staging, no lock, no scratch).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }
std::string hba() { return quoted(test::cliPath()); }

// Names in `dir`, hidden ones included.
std::vector<std::string> namesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class OutputRule : public testing::Test {
 protected:
  void SetUp() override {
    const test::CommandResult sim =
        test::runCommand(hba() + " -q simulate --frames 150 --seed 3 -o " + quoted(dir / "sim"));
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
  }
  std::string optimize(const std::string& extra) const {
    return hba() + " -q optimize " + quoted(dir / "sim") + " -o " + quoted(dir / "out") + " " + extra;
  }
  test::TempDir dir;
};

TEST_F(OutputRule, NonEmptyFolderNeedsForceWhichReplacesItWhole) {
  // An earlier hba output (its marker) with a picture this run will not draw.
  fs::create_directories(dir / "out");
  test::writeText(dir / "out" / ".hba-output", "");
  test::writeText(dir / "out" / "before_after.png", "an earlier run's picture");
  const test::CommandResult refused = test::runCommand(optimize("--no-render --layers 1"));
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("not empty (use --force"), std::string::npos) << refused.output;
  EXPECT_EQ(test::readText(dir / "out" / "before_after.png"), "an earlier run's picture");
  const test::CommandResult forced = test::runCommand(optimize("--no-render --layers 1 --force"));
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "pose.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "before_after.png")) << "no earlier file beside the new ones";
  EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"out", "sim"}));  // no staging, no lock left
}

TEST_F(OutputRule, SecondRunIntoAFolderInUseIsRefused) {
  // The first run holds the folder for seconds; the second starts meanwhile.
  const std::string first = optimize("--no-render > " + quoted(dir / "first.log") + " 2>&1");
  ASSERT_EQ(std::system((first + " &").c_str()), 0);  // system's shell runs it in the background
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  const test::CommandResult second = test::runCommand(optimize("--no-render --force"));
  EXPECT_NE(second.exit_code, 0);
  EXPECT_NE(second.output.find("another hba run is writing this output"), std::string::npos) << second.output;
  // The first finishes untroubled: waited for as long as it takes (ctest's
  // time limit ends a hang), since a slow build (ThreadSanitizer: minutes)
  // runs long past a fixed wait.
  for (int i = 0; i < 36000 && !fs::exists(dir / "out" / "pose.json"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(fs::exists(dir / "out" / "report.json"));
}

TEST_F(OutputRule, CtrlCLeavesNothingBehind) {
  // A script that records hba's pid, then becomes hba; its exit code is kept.
  test::writeText(dir / "run.sh", "echo $$ > " + quoted(dir / "hba.pid") + "\nexec " +
                                      optimize("--no-render > " + quoted(dir / "run.log") + " 2>&1") + "\n");
  ASSERT_EQ(
      std::system(
          ("(sh " + quoted(dir / "run.sh") + "; echo $? > " + quoted(dir / "exit.txt") + ") &").c_str()),
      0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_TRUE(fs::exists(dir / "hba.pid"));
  ASSERT_EQ(::kill(static_cast<pid_t>(std::stol(test::readText(dir / "hba.pid"))), SIGINT), 0);  // as Ctrl-C
  for (int i = 0; i < 100 && !fs::exists(dir / "exit.txt"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(fs::exists(dir / "exit.txt"));
  EXPECT_EQ(std::stoi(test::readText(dir / "exit.txt")), 130);
  EXPECT_NE(test::readText(dir / "run.log").find("interrupted"), std::string::npos)
      << test::readText(dir / "run.log");
  EXPECT_EQ(namesIn(dir.path()),
            (std::vector<std::string>{"exit.txt", "hba.pid", "run.log", "run.sh", "sim"}));
}

}  // namespace
}  // namespace hba
