// Hostile inputs that are not bad bytes but bad places (issue #35): a FIFO
// named like a scan, symbolic link loops, a folder named with a byte that is
// not UTF-8, a TMPDIR that does not exist, /dev/stdin, a byte order mark.
// Each command ends (under `timeout`), says what is wrong and where, and
// leaves its input as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "cli_runs.hpp"
#include "folder_snapshot.hpp"
#include "hba/io/pose_file.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::quoted;
using test::TempDir;

class SpecialInputs : public testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> truth = test::straightPath(8);
    test::writeSceneDataset(data(), test::roomScene(1000), truth, test::perturbed(truth, 0.03, 0.3, 3));
  }
  fs::path data() const { return tmp_ / "data"; }
  fs::path out() const { return tmp_ / "out"; }
  // `hba -j 1 <arguments>`, stopped after a minute: a hang fails the test.
  static test::CommandResult hba(const std::string& arguments, const std::string& environment = "") {
    return test::runCommand(environment + " timeout 60 " + quoted(test::cliPath()) + " -j 1 " + arguments);
  }
  // Every reading command on the dataset fails (exit 1), in time, saying `pieces`.
  void expectEveryCommandRefuses(const std::vector<std::string>& pieces) const {
    const std::string d = quoted(data());
    for (const std::string& command :
         {"info " + d, "optimize " + d + " -o " + quoted(out()), "map " + d + " -o " + quoted(tmp_ / "m.pcd"),
          "mme " + d, "render " + d + " -o " + quoted(tmp_ / "m.png")}) {
      const test::CommandResult run = hba(command);
      EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.output;
      for (const std::string& piece : pieces) {
        EXPECT_NE(run.output.find(piece), std::string::npos) << command << ": no '" << piece << "' in\n"
                                                             << run.output;
      }
      EXPECT_FALSE(fs::exists(out())) << command;
    }
  }

  TempDir tmp_;
};

TEST_F(SpecialInputs, AFifoNamedLikeAScanIsRefusedNotWaitedFor) {
  fs::remove(data() / "pcd" / "3.pcd");
  ASSERT_EQ(::mkfifo((data() / "pcd" / "3.pcd").c_str(), 0600), 0);
  const test::FolderSnapshot before = test::snapshotFolder(data());
  expectEveryCommandRefuses({(data() / "pcd" / "3.pcd").string(), "is not a regular file (a FIFO)"});
  EXPECT_EQ(test::snapshotFolder(data()), before);
}

TEST_F(SpecialInputs, SymbolicLinkLoopsAreCalledSo) {
  const std::string scan = test::readText(data() / "pcd" / "3.pcd");
  fs::remove(data() / "pcd" / "3.pcd");
  fs::create_symlink("3.pcd", data() / "pcd" / "3.pcd");
  const test::FolderSnapshot before = test::snapshotFolder(data());
  expectEveryCommandRefuses({"3.pcd", "is a symbolic link loop"});
  EXPECT_EQ(test::snapshotFolder(data()), before);
  fs::remove(data() / "pcd" / "3.pcd");
  test::writeText(data() / "pcd" / "3.pcd", scan);

  fs::create_symlink("b.txt", tmp_ / "a.txt");
  fs::create_symlink("a.txt", tmp_ / "b.txt");
  const test::CommandResult poses = hba("info " + quoted(data()) + " --poses " + quoted(tmp_ / "a.txt"));
  EXPECT_EQ(poses.exit_code, 1) << poses.output;
  EXPECT_NE(poses.output.find("a.txt: is a symbolic link loop"), std::string::npos) << poses.output;
  const test::CommandResult eval =
      hba("eval --gt " + quoted(tmp_ / "a.txt") + " --est " + quoted(tmp_ / "b.txt"));
  EXPECT_EQ(eval.exit_code, 2) << eval.output;  // a flag's bad value
  EXPECT_NE(eval.output.find("a.txt: is a symbolic link loop"), std::string::npos) << eval.output;
  fs::create_directory_symlink("dir_b", tmp_ / "dir_a");
  fs::create_directory_symlink("dir_a", tmp_ / "dir_b");
  const test::CommandResult dir = hba("info " + quoted(tmp_ / "dir_a"));
  EXPECT_EQ(dir.exit_code, 1) << dir.output;
  EXPECT_NE(dir.output.find("dir_a: is a symbolic link loop"), std::string::npos) << dir.output;
}

// A ground-truth file that cannot be read fails the run before its work, not
// after it (the picture and the report page, which draw it, come last).
// Without either, it is not read.
TEST_F(SpecialInputs, ABadGroundTruthFailsBeforeTheWork) {
  ASSERT_EQ(::mkfifo((data() / "gt.txt").c_str(), 0600), 0);
  const test::CommandResult run = hba("optimize " + quoted(data()) + " -o " + quoted(out()));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("gt.txt: is not a regular file (a FIFO)"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("layer"), std::string::npos) << run.output;  // no optimization ran
  // Without the picture and the page it is still read: report.json's
  // window_errors measure the windows against it.
  const test::CommandResult unpictured =
      hba("optimize " + quoted(data()) + " -o " + quoted(out()) + " --no-render --no-report-page");
  EXPECT_EQ(unpictured.exit_code, 1) << unpictured.output;
  EXPECT_NE(unpictured.output.find("gt.txt: is not a regular file (a FIFO)"), std::string::npos)
      << unpictured.output;
}

// A byte that is not UTF-8 in the dataset's path: nlohmann's dump() threw at
// the very end of a run ([json.exception.type_error.316]) and lost it.
TEST_F(SpecialInputs, AFolderNamedWithAByteThatIsNotUtf8) {
  const fs::path odd = tmp_ / "data\xff";
  fs::rename(data(), odd);
  const test::FolderSnapshot before = test::snapshotFolder(odd);
  const test::CommandResult run = hba("optimize " + quoted(odd) + " -o " + quoted(out()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json report = nlohmann::json::parse(test::readText(out() / "report.json"));
  EXPECT_NE(report.at("input").at("dataset").get<std::string>().find("data\xEF\xBF\xBD"), std::string::npos);
  test::expectFiniteOptimizeOutputs(out(), 8);

  const test::CommandResult info = hba("info --json " + quoted(odd));
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_TRUE(nlohmann::json::accept(info.output.substr(info.output.find('{')))) << info.output;

  const test::CommandResult eval = hba("eval --gt " + quoted(odd / "pose.json") + " --est " +
                                       quoted(out() / "pose.json") + " --json " + quoted(tmp_ / "eval.json"));
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_TRUE(nlohmann::json::accept(test::readText(tmp_ / "eval.json")));
  EXPECT_EQ(test::snapshotFolder(odd), before);
}

TEST_F(SpecialInputs, AMissingTmpdirIsNamedBeforeAnyWork) {
  const test::CommandResult run =
      hba("optimize " + quoted(data()) + " -o " + quoted(out()), "TMPDIR=/nonexistent/hba-scratch");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("/nonexistent/hba-scratch: temporary folder not found"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("TMPDIR"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(out()));
}

// /dev/stdin is read when it leads to a file (`< poses.txt`), refused when it
// is a pipe: hba reads a pose file twice (its format, then its poses).
TEST_F(SpecialInputs, StdinIsReadWhenItIsAFile) {
  const std::string gt = quoted(data() / "pose.json");
  const test::CommandResult file = hba("eval --gt /dev/stdin --est " + gt + " < " + gt);
  EXPECT_EQ(file.exit_code, 0) << file.output;
  const test::CommandResult pipe = test::runCommand("cat " + gt + " | timeout 60 " + quoted(test::cliPath()) +
                                                    " eval --gt /dev/stdin --est " + gt);
  EXPECT_EQ(pipe.exit_code, 2) << pipe.output;
  EXPECT_NE(pipe.output.find("is not a regular file (a FIFO)"), std::string::npos) << pipe.output;
}

TEST_F(SpecialInputs, AByteOrderMarkIsInvisibleToo) {
  const std::string poses = test::readText(data() / "pose.json");
  test::writeText(data() / "pose.json", "\xEF\xBB\xBF" + poses);
  const test::CommandResult info = hba("info " + quoted(data()));
  EXPECT_EQ(info.exit_code, 0) << info.output;
  test::writeText(tmp_ / "settings.yaml", "\xEF\xBB\xBFwindow: 12\n");
  const test::CommandResult config =
      hba("optimize --print-config --config " + quoted(tmp_ / "settings.yaml"));
  EXPECT_EQ(config.exit_code, 0) << config.output;
  EXPECT_NE(config.output.find("window: 12"), std::string::npos) << config.output;
}

}  // namespace
}  // namespace hba
