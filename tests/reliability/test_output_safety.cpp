// What hba writes never destroys what it did not write: --force replaces
// only an earlier hba output, no output (nor the log) replaces an input of
// the run, a result that could not be written fails the run, and two runs
// never write one output at once. Every hostile case runs on copies whose
// bytes are hashed before and after.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include "cli_runs.hpp"
#include "folder_snapshot.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::quoted;
using test::TempDir;

bool says(const test::CommandResult& run, const std::string& text) {
  return run.output.find(text) != std::string::npos;
}

class OutputSafety : public testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> truth = test::straightPath(8);
    test::writeSceneDataset(data(), test::roomScene(800), truth, test::perturbed(truth, 0.03, 0.3, 3));
    data_before_ = test::snapshotFolder(data());
  }
  void TearDown() override { EXPECT_EQ(test::snapshotFolder(data()), data_before_) << "the input changed"; }
  fs::path data() const { return tmp_ / "data"; }
  // `hba optimize` with no picture (the runs stay short).
  test::CommandResult optimize(const fs::path& out, const std::string& extra = "") const {
    return test::runOptimize(data(), out, "--no-render " + extra);
  }

  TempDir tmp_;
  test::FolderSnapshot data_before_;
};

// Item 1: `hba optimize in -o victim --force` deleted a folder of the user's.
TEST_F(OutputSafety, ForceNeverDeletesAFolderHbaDidNotWrite) {
  const fs::path victim = tmp_ / "victim";
  fs::create_directories(victim / "sub");
  test::writeText(victim / "thesis.tex", "\\documentclass{article}\n");
  test::writeText(victim / "sub" / "data.csv", "1,2,3\n");
  const test::FolderSnapshot before = test::snapshotFolder(victim);
  const test::CommandResult run = optimize(victim, "--force");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(says(run, "hba did not write")) << run.output;
  EXPECT_EQ(test::snapshotFolder(victim), before);
}

TEST_F(OutputSafety, ForceReplacesAnEarlierOutputAndSaysSo) {
  const fs::path out = tmp_ / "out";
  ASSERT_EQ(optimize(out).exit_code, 0);
  EXPECT_TRUE(fs::exists(out / ".hba-output"));
  const test::CommandResult again = optimize(out, "--force");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_TRUE(says(again, "holds an earlier hba output")) << again.output;
  EXPECT_TRUE(fs::exists(out / "pose.json"));
}

TEST_F(OutputSafety, AnEmptyFolderIsUsedWithoutForce) {
  fs::create_directories(tmp_ / "empty");
  EXPECT_EQ(optimize(tmp_ / "empty").exit_code, 0);
}

TEST_F(OutputSafety, ForceNeverReplacesTheCurrentFolderTheRootOrHome) {
  const fs::path here = tmp_ / "here";
  fs::create_directories(here / "inner");
  test::writeText(here / "notes.txt", "mine\n");
  const test::FolderSnapshot before = test::snapshotFolder(here);
  const std::string tool = quoted(test::cliPath());
  const std::string opt = " -j 1 optimize " + quoted(data()) + " --no-render --force -o ";
  // The current folder, an empty one, and the folder holding it.
  for (const std::string& command : {"cd " + quoted(here) + " && " + tool + opt + ".",
                                     "cd " + quoted(here / "inner") + " && " + tool + opt + ".",
                                     "cd " + quoted(here / "inner") + " && " + tool + opt + ".."}) {
    const test::CommandResult run = test::runCommand(command);
    EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.output;
    EXPECT_TRUE(says(run, "current folder")) << run.output;
  }
  EXPECT_EQ(test::snapshotFolder(here), before);
  const test::CommandResult root = test::runHba(opt + "/");
  EXPECT_EQ(root.exit_code, 1) << root.output;
  EXPECT_TRUE(says(root, "root folder")) << root.output;
  const test::CommandResult home = test::runCommand("HOME=" + quoted(here) + " " + tool + opt + quoted(here));
  EXPECT_EQ(home.exit_code, 1) << home.output;
  EXPECT_TRUE(says(home, "home folder")) << home.output;
  EXPECT_EQ(test::snapshotFolder(here), before);
}

// Item 2: the run's own input trajectory inside the folder it replaces.
TEST_F(OutputSafety, OptimizeNeverReplacesAFolderHoldingItsInput) {
  const fs::path run1 = tmp_ / "run1";
  ASSERT_EQ(optimize(run1).exit_code, 0);
  const test::FolderSnapshot before = test::snapshotFolder(run1);
  const test::CommandResult run = optimize(run1, "--force --poses " + quoted(run1 / "pose.json"));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(says(run, "an input of this run")) << run.output;
  EXPECT_EQ(test::snapshotFolder(run1), before);
}

TEST_F(OutputSafety, EvalNeverWritesOverItsEstimate) {
  const fs::path est = tmp_ / "est.txt";
  fs::copy_file(data() / "pose.json", est);
  const std::string bytes = test::readText(est);
  for (const std::string flag : {"--json", "--plot"}) {
    const std::string target = flag == std::string("--plot") ? quoted(tmp_ / "est.png") : quoted(est);
    if (flag == std::string("--plot")) fs::copy_file(est, tmp_ / "est.png");
    const test::CommandResult run = test::runHba("eval --gt " + quoted(data() / "pose.json") + " --est " +
                                                 target + " " + flag + " " + target + " --force");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(says(run, "is an input of this run")) << run.output;
  }
  EXPECT_EQ(test::readText(est), bytes);
}

// Item 3: the log appended to the input trajectory; a log nowhere; a log
// inside the folder the run replaces.
TEST_F(OutputSafety, TheLogFileIsNeverAnInputNorInsideAnOutput) {
  const std::string d = quoted(data());
  const test::CommandResult into_input =
      test::runHba("--log-file " + quoted(data() / "pose.json") + " info " + d);
  EXPECT_EQ(into_input.exit_code, 1) << into_input.output;
  EXPECT_TRUE(says(into_input, "input of this run")) << into_input.output;

  const test::CommandResult nowhere = test::runHba("--log-file /nonexistent/dir/log.txt info " + d);
  EXPECT_EQ(nowhere.exit_code, 1) << nowhere.output;
  EXPECT_TRUE(says(nowhere, "/nonexistent/dir does not exist")) << nowhere.output;
  EXPECT_FALSE(fs::exists("/nonexistent"));

  const fs::path out = tmp_ / "out";
  const test::CommandResult inside = test::runHba("--log-file " + quoted(out / "log.txt") +
                                                  " -j 1 optimize " + d + " --no-render -o " + quoted(out));
  EXPECT_EQ(inside.exit_code, 1) << inside.output;
  EXPECT_TRUE(says(inside, "put the log beside it")) << inside.output;
  EXPECT_FALSE(fs::exists(out));

  const fs::path thesis = tmp_ / "thesis.tex";
  test::writeText(thesis, "\\documentclass{article}\n");
  const test::CommandResult other = test::runHba("--log-file " + quoted(thesis) + " info " + d);
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(says(other, "is not an hba log")) << other.output;
  EXPECT_EQ(test::readText(thesis), "\\documentclass{article}\n");
}

TEST_F(OutputSafety, TheLogFileIsAppendedToAcrossRuns) {
  const fs::path log = tmp_ / "hba.log";
  std::string previous;
  for (int i = 0; i < 2; ++i) {
    const test::CommandResult run = test::runHba("-q --log-file " + quoted(log) + " info " + quoted(data()));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string text = test::readText(log);
    EXPECT_EQ(text.rfind(previous, 0), 0u) << "the earlier lines are kept";
    EXPECT_GT(text.size(), previous.size());
    EXPECT_EQ(text.rfind("[20", 0), 0u) << text;
    previous = text;
  }
}

// Item 4: results lost with exit 0 (stdout on a full disk, closed).
TEST_F(OutputSafety, AResultThatCannotBeWrittenFailsTheRun) {
  const std::string tool = quoted(test::cliPath());
  const std::string d = quoted(data());
  const std::string est = quoted(data() / "pose.json");
  for (const std::string& command :
       std::vector<std::string>{"mme " + d, "info " + d, "info --json " + d,
                                "eval --gt " + est + " --est " + est, "optimize --print-config"}) {
    for (const std::string redirect : {" >/dev/full", " >&-"}) {
      const test::CommandResult run = test::runCommand("{ " + tool + " -j 1 " + command + redirect + "; }");
      EXPECT_EQ(run.exit_code, 1) << command << redirect << "\n" << run.output;
      EXPECT_TRUE(says(run, "cannot write the results to standard output"))
          << command << redirect << run.output;
    }
  }
}

// Item 9: two `hba map` runs into one file: the second is refused, not
// silently overwritten. A lock held by this test stands in for the first run.
TEST_F(OutputSafety, ASecondRunIntoTheSameFileIsRefused) {
  const fs::path map = tmp_ / "map.pcd";
  const fs::path lock = tmp_ / ".map.pcd.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const test::CommandResult run = test::runHba("map " + quoted(data()) + " -o " + quoted(map));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(says(run, "another hba run is writing this output")) << run.output;
  EXPECT_FALSE(fs::exists(map));
  ::close(fd);
  const test::CommandResult free = test::runHba("map " + quoted(data()) + " -o " + quoted(map));
  EXPECT_EQ(free.exit_code, 0) << free.output;
  EXPECT_FALSE(fs::exists(lock)) << "the lock file is removed after the run";
}

}  // namespace
}  // namespace hba
