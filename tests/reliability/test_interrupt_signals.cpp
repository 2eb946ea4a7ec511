// Ctrl-C, SIGTERM or SIGHUP at any point of `extract`, `optimize` or a
// `--force` swap leaves OUT either the complete new output, or as it was
// before the run (absent, or the complete earlier output); the last line
// says which; and no hidden staging folder or temporary is left beside it.
//
// Exact points (the middle of a swap) are reached with the tool's test hook
// HBA_TEST_INTERRUPT_AT (the process signals itself there); the others by
// signalling a running process after a range of delays.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::quoted;
using test::TempDir;

struct Signal {
  int number;
  const char* name;  // as HBA_TEST_INTERRUPT_SIGNAL takes it
};
const Signal kSignals[] = {{SIGINT, "INT"}, {SIGTERM, "TERM"}};

// Files and folders beside `out` that belong to it but are hidden: staging
// folders, earlier outputs moved aside, locks, temporaries.
std::vector<std::string> hiddenLeftovers(const fs::path& out) {
  std::vector<std::string> left;
  const std::string prefix = "." + out.filename().string();
  for (const fs::directory_entry& entry : fs::directory_iterator(out.parent_path())) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0) left.push_back(name);
  }
  if (fs::is_directory(out)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(out)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(".", 0) == 0 && name != ".hba-output") left.push_back(entry.path().string());
    }
  }
  return left;
}

// An extract output of `scans` scans, complete: marker, every scan readable,
// pose.json with every pose.
void expectCompleteExtract(const fs::path& out, std::size_t scans) {
  ASSERT_TRUE(fs::is_regular_file(out / ".hba-output")) << out;
  ASSERT_TRUE(fs::is_regular_file(out / "pose.json")) << out;
  EXPECT_EQ(io::readPoses(out / "pose.json").size(), scans) << out;
  std::size_t found = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(out / "pcd")) {
    EXPECT_NO_THROW(io::readPcd(entry.path())) << entry.path();
    ++found;
  }
  EXPECT_EQ(found, scans) << out;
}

bool says(const std::string& output, const std::string& text) {
  return output.find(text) != std::string::npos;
}

// Runs the tool with the interrupt hook at `point` (NAME or NAME:N).
test::CommandResult runInterruptedAt(const std::string& point, const Signal& signal,
                                     const std::string& arguments, const std::string& environment = "") {
  return test::runCommand(environment + "HBA_TEST_INTERRUPT_AT=" + point + " HBA_TEST_INTERRUPT_SIGNAL=" +
                          signal.name + " " + quoted(test::cliPath()) + " " + arguments);
}

class InterruptSignals : public testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> path = test::straightPath(kScans);
    test::writeSceneDataset(tmp_ / "data", test::roomScene(800), path, path);
    const std::vector<Pose> shorter = test::straightPath(kEarlierScans);
    test::writeSceneDataset(tmp_ / "earlier_data", test::roomScene(800), shorter, shorter);
  }
  // OUT holding a complete extract of the shorter dataset.
  fs::path earlierOutput(const std::string& name) {
    const fs::path out = tmp_ / name;
    const test::CommandResult run =
        test::runHba("-q extract " + quoted(tmp_ / "earlier_data") + " -o " + quoted(out));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return out;
  }
  static constexpr std::size_t kScans = 12;
  static constexpr std::size_t kEarlierScans = 5;
  TempDir tmp_;
};

TEST_F(InterruptSignals, DuringTheScansNothingIsLeftAndTheMessageSaysSo) {
  for (const Signal& signal : kSignals) {
    for (const std::size_t scan : {std::size_t{1}, kScans / 2, kScans - 1, kScans}) {
      SCOPED_TRACE(std::string(signal.name) + " after scan " + std::to_string(scan));
      const fs::path out = tmp_ / ("out_" + std::string(signal.name) + std::to_string(scan));
      const test::CommandResult run =
          runInterruptedAt("scan-written:" + std::to_string(scan), signal,
                           "extract " + quoted(tmp_ / "data") + " -o " + quoted(out));
      EXPECT_EQ(run.exit_code, 128 + signal.number) << run.output;
      EXPECT_FALSE(fs::exists(out)) << run.output;
      EXPECT_TRUE(says(run.output, "the unfinished output was removed: " + out.string() + " was not created"))
          << run.output;
      EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>());
    }
  }
}

// Found under ThreadSanitizer (a slow build, so an early Ctrl-C): an
// interrupt between making the lock file or the staging folder and
// registering it for removal left `.OUT.lock` and `.OUT.partial-PID` behind.
TEST_F(InterruptSignals, AsTheOutputIsLockedAndStagedNothingIsLeft) {
  for (const Signal& signal : kSignals) {
    for (const char* point : {"output-locking", "staging-made"}) {
      SCOPED_TRACE(std::string(signal.name) + " at " + point);
      const fs::path out = tmp_ / ("early_" + std::string(signal.name) + point);
      // The watcher pauses between its removal and the exit, while the run
      // goes on making the lock and the staging folder.
      const test::CommandResult run =
          runInterruptedAt(point, signal, "extract " + quoted(tmp_ / "data") + " -o " + quoted(out),
                           "HBA_TEST_INTERRUPT_PAUSE_MS=400 ");
      EXPECT_EQ(run.exit_code, 128 + signal.number) << run.output;
      EXPECT_FALSE(fs::exists(out)) << run.output;
      EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>()) << run.output;
      EXPECT_TRUE(says(run.output, "interrupted")) << run.output;
    }
  }
}

TEST_F(InterruptSignals, DuringTheScansOfAForcedRunTheEarlierOutputStays) {
  for (const Signal& signal : kSignals) {
    SCOPED_TRACE(signal.name);
    const fs::path out = earlierOutput(std::string("forced_") + signal.name);
    const test::CommandResult run =
        runInterruptedAt("scan-written:" + std::to_string(kScans - 1), signal,
                         "extract " + quoted(tmp_ / "data") + " -o " + quoted(out) + " --force");
    EXPECT_EQ(run.exit_code, 128 + signal.number) << run.output;
    expectCompleteExtract(out, kEarlierScans);
    EXPECT_TRUE(says(run.output, out.string() + " holds the earlier output, unchanged")) << run.output;
    EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>());
  }
}

// The swap of a --force run is waited for: OUT is then the new output, whole.
TEST_F(InterruptSignals, DuringTheSwapTheNewOutputIsCompleteAndTheMessageSaysSo) {
  for (const Signal& signal : kSignals) {
    for (const char* point : {"swap-begin", "swap-middle", "swap-end", "old-removal"}) {
      SCOPED_TRACE(std::string(signal.name) + " at " + point);
      const fs::path out = earlierOutput(std::string("swap_") + signal.name + "_" + point);
      const test::CommandResult run = runInterruptedAt(
          point, signal, "extract " + quoted(tmp_ / "data") + " -o " + quoted(out) + " --force");
      EXPECT_EQ(run.exit_code, 128 + signal.number) << run.output;
      expectCompleteExtract(out, kScans);
      EXPECT_TRUE(says(run.output, out.string() + " was complete before the interrupt")) << run.output;
      EXPECT_FALSE(says(run.output, "removed")) << run.output;
      EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>());
    }
  }
}

TEST_F(InterruptSignals, AFirstRunInterruptedAtTheFinalRenameIsComplete) {
  for (const Signal& signal : kSignals) {
    SCOPED_TRACE(signal.name);
    const fs::path out = tmp_ / (std::string("first_") + signal.name);
    const test::CommandResult run =
        runInterruptedAt("swap-begin", signal, "extract " + quoted(tmp_ / "data") + " -o " + quoted(out));
    EXPECT_EQ(run.exit_code, 128 + signal.number) << run.output;
    expectCompleteExtract(out, kScans);
    EXPECT_TRUE(says(run.output, out.string() + " was complete before the interrupt")) << run.output;
    EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>());
  }
}

// Whatever the moment: a run that was cut short says what OUT holds, and it
// does; a run that finished first exits 0 with OUT complete.
void expectOutcomeAsSaid(const test::CommandResult& run, int signal, const fs::path& out,
                         const std::function<void()>& expect_new,
                         const std::function<void()>& expect_before) {
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 128 + signal) << run.output;
  if (run.exit_code == 0 || says(run.output, out.string() + " was complete before the interrupt")) {
    expect_new();
  } else if (says(run.output, out.string() + " holds the earlier output, unchanged") ||
             says(run.output, out.string() + " was not created")) {
    expect_before();
  } else if (!says(run.output, "unfinished output")) {
    // Interrupted before the output was begun: OUT as it was.
    expect_before();
  } else {
    ADD_FAILURE() << "the message does not say what " << out << " holds: " << run.output;
  }
  EXPECT_EQ(hiddenLeftovers(out), std::vector<std::string>());
}

TEST_F(InterruptSignals, AtAnyMomentOfExtractOutIsWholeOrAsBefore) {
  int run_index = 0;
  for (const int delay_ms : {5, 20, 40, 70, 100, 150, 220, 300, 450, 700}) {
    const Signal& signal = kSignals[run_index++ % 2];
    SCOPED_TRACE(std::to_string(delay_ms) + " ms, " + signal.name);
    const fs::path out = earlierOutput("timed_" + std::to_string(delay_ms));
    const test::CommandResult run =
        test::runAndSignal({"extract", (tmp_ / "data").string(), "-o", out.string(), "--force"},
                           signal.number, std::chrono::milliseconds(delay_ms), tmp_ / "log.txt");
    expectOutcomeAsSaid(
        run, signal.number, out, [&] { expectCompleteExtract(out, kScans); },
        [&] { expectCompleteExtract(out, kEarlierScans); });
  }
}

TEST_F(InterruptSignals, AtAnyMomentOfOptimizeOutIsWholeOrAbsent) {
  int run_index = 0;
  for (const int delay_ms : {10, 50, 120, 250, 400, 600, 900, 1300, 1800, 2500}) {
    const Signal& signal = kSignals[run_index++ % 2];
    SCOPED_TRACE(std::to_string(delay_ms) + " ms, " + signal.name);
    const fs::path out = tmp_ / ("optimized_" + std::to_string(delay_ms));
    const test::CommandResult run =
        test::runAndSignal({"optimize", (tmp_ / "data").string(), "-o", out.string()}, signal.number,
                           std::chrono::milliseconds(delay_ms), tmp_ / "log.txt");
    expectOutcomeAsSaid(
        run, signal.number, out, [&] { test::expectFiniteOptimizeOutputs(out, kScans); },
        [&] { EXPECT_FALSE(fs::exists(out)) << run.output; });
  }
}

}  // namespace
}  // namespace hba
