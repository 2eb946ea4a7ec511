// hba never writes into its input: every command that reads a dataset leaves
// the dataset folder byte for byte as it was, and refuses an output inside it.
#include <gtest/gtest.h>

#include "cli_runs.hpp"
#include "folder_snapshot.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::quoted;
using test::TempDir;

class InputUntouched : public testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> truth = test::straightPath(8);
    test::writeSceneDataset(data(), test::roomScene(1000), truth, test::perturbed(truth, 0.03, 0.3, 3));
    before_ = test::snapshotFolder(data());
  }
  fs::path data() const { return tmp_ / "data"; }
  fs::path out() const { return tmp_ / "out"; }
  void expectInputUnchanged() const { EXPECT_EQ(test::snapshotFolder(data()), before_); }

  TempDir tmp_;
  test::FolderSnapshot before_;
};

TEST_F(InputUntouched, EveryCommandLeavesTheDatasetAsItWas) {
  const std::string d = quoted(data());
  fs::create_directories(out());
  const std::vector<std::string> commands = {
      "info " + d,
      "optimize " + d + " -o " + quoted(out() / "opt"),
      "map " + d + " -o " + quoted(out() / "map.pcd"),
      "map " + d + " -o " + quoted(out() / "map.ply"),
      "mme " + d,
      "render " + d + " -o " + quoted(out() / "map.png") + " --width 600 --height 400",
      "eval --gt " + quoted(data() / "pose.json") + " --est " + quoted(out() / "opt" / "pose.json") +
          " --json " + quoted(out() / "eval.json"),
  };
  for (const std::string& command : commands) {
    const test::CommandResult run = test::runHba("-j 1 " + command);
    EXPECT_EQ(run.exit_code, 0) << command << "\n" << run.output;
    expectInputUnchanged();
  }
}

TEST_F(InputUntouched, OptimizeRefusesAnOutputInsideTheInput) {
  for (const fs::path& inside : {data(), data() / "result", data() / "pcd"}) {
    const test::CommandResult run = test::runOptimize(data(), inside);
    EXPECT_NE(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("never writes into its input"), std::string::npos) << run.output;
    expectInputUnchanged();
  }
}

TEST_F(InputUntouched, MapRefusesAnOutputAmongTheScans) {
  const test::CommandResult run =
      test::runHba("map " + quoted(data()) + " -o " + quoted(data() / "pcd" / "map.pcd"));
  EXPECT_NE(run.exit_code, 0) << run.output;
  expectInputUnchanged();
}

// Not even beside the scans: the dataset folder is input too.
TEST_F(InputUntouched, MapRefusesAnOutputInTheDatasetFolder) {
  const test::CommandResult run = test::runHba("map " + quoted(data()) + " -o " + quoted(data() / "map.pcd"));
  EXPECT_NE(run.exit_code, 0) << run.output;
  expectInputUnchanged();
}

}  // namespace
}  // namespace hba
