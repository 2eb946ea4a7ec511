// A run killed midway (kill -9: no cleanup code runs) leaves no half-written
// file under a final name: every output that exists is complete. Files are
// written to hidden temporaries and renamed into place, and `hba simulate`
// builds its whole folder beside the destination before moving it in.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <thread>

#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

extern char** environ;

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::TempDir;

// Starts `hba <arguments...>` with its output discarded, waits `delay`, then
// kills it with SIGKILL (if it has not finished) and reaps it.
void runAndKill(const std::vector<std::string>& arguments, std::chrono::milliseconds delay) {
  std::vector<std::string> words = {test::cliPath().string(), "-q"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ASSERT_EQ(spawned, 0) << "cannot start " << argv[0];
  std::this_thread::sleep_for(delay);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
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
