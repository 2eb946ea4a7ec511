// A run killed midway (kill -9: no cleanup code runs) leaves no half-written
// file under a final name: every output that exists is complete. Files are
// written to hidden temporaries and renamed into place, and `hba simulate`
// builds its whole folder beside the destination before moving it in.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>

#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

// Runs `hba <arguments...>`, kills it with SIGKILL after `delay` (if it has
// not finished) and reaps it.
void runAndKill(const std::vector<std::string>& arguments, std::chrono::milliseconds delay) {
  test::runAndSignal(arguments, SIGKILL, delay);
}

// Every visible (final-name) file below `root` parses completely.
void expectOnlyCompleteFiles(const fs::path& root, std::size_t pose_count) {
  if (!fs::exists(root)) return;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const fs::path& file = entry.path();
    const std::string name = file.filename().string();
    if (name.front() == '.') continue;  // a temporary: never a final name
    SCOPED_TRACE(file.string());
    try {
      if (file.extension() == ".pcd") {
        io::readPcd(file);
      } else if (name == "pose.json" || name == "poses_kitti.txt" || name == "poses_tum.txt" ||
                 name == "gt.txt") {
        EXPECT_EQ(io::readPoses(file).size(), pose_count);
      } else if (file.extension() == ".json") {
        EXPECT_FALSE(test::readText(file).empty());
      }
    } catch (const Error& e) {
      ADD_FAILURE() << "half-written output: " << e.what();
    }
  }
}

// Hidden folders (staging) and temporaries may remain after SIGKILL; no
// visible folder may be partially filled.
TEST(InterruptedRuns, KilledSimulateLeavesNoPartialSequence) {
  TempDir tmp;
  for (const int delay_ms : {50, 300, 700, 1200}) {
    const fs::path out = tmp / ("sim_" + std::to_string(delay_ms));
    runAndKill({"simulate", "--frames", "40", "--downsample", "0.5", "-o", out.string()},
               std::chrono::milliseconds(delay_ms));
    if (fs::exists(out)) {
      // A visible sequence folder is a finished one: all 40 scans and poses.
      EXPECT_TRUE(fs::exists(out / "pose.json")) << out;
      EXPECT_TRUE(fs::exists(out / "pcd" / "000039.pcd")) << out;
    }
    expectOnlyCompleteFiles(tmp.path(), 40);
  }
}

TEST(InterruptedRuns, KilledOptimizeLeavesNoPartialPoses) {
  TempDir tmp;
  const std::vector<Pose> truth = test::straightPath(20);
  test::writeSceneDataset(tmp / "data", test::roomScene(), truth, test::perturbed(truth, 0.03, 0.3, 5));
  for (const int delay_ms : {50, 200, 400, 800}) {
    const fs::path out = tmp / ("out_" + std::to_string(delay_ms));
    runAndKill({"optimize", (tmp / "data").string(), "-o", out.string()},
               std::chrono::milliseconds(delay_ms));
    expectOnlyCompleteFiles(out, 20);
  }
}

}  // namespace
}  // namespace hba
