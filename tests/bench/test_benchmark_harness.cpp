// The benchmark harness (scripts/bench) on its smallest quick scenario: an
// honest run passes and fills BENCHMARKS.md's generated section without
// touching the hand-written text; a run whose optimized poses are worse than
// the initial ones fails loudly, so a speed-up can never hide an accuracy loss.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace {
namespace fs = std::filesystem;
using hba::test::runCommand;

const char* const kHandWritten = "# Benchmarks\n\nIntro.\n\n## Hand-written\n\nkeep me\n";

bool pythonAvailable() { return runCommand("command -v python3").exit_code == 0; }

// The harness on one tiny scenario, everything inside `dir`; `environment`
// holds NAME=value words for the harness and its children.
hba::test::CommandResult runHarness(const hba::test::TempDir& dir, const std::string& hba,
                                    const std::string& environment = "") {
  return runCommand("env " + environment +
                    " python3 " HBA_SOURCE_DIR
                    "/scripts/bench/run_benchmarks.py --quick"
                    " --only sim-livox-100-drift --jobs 1 --hba " +
                    hba + " --io-floor " HBA_IO_FLOOR_PATH " --data-dir " + (dir / "data").string() +
                    " --output " + (dir / "BENCHMARKS.md").string() + " --results-dir " +
                    (dir / "results").string());
}

TEST(BenchmarkHarness, AnHonestRunPassesAndKeepsTheHandWrittenText) {
  if (!pythonAvailable()) GTEST_SKIP() << "python3 is not installed";
  hba::test::TempDir dir;
  hba::test::writeText(dir / "BENCHMARKS.md", kHandWritten);
  const auto run = runHarness(dir, hba::test::cliPath().string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("ACCURACY REGRESSION"), std::string::npos) << run.output;

  const std::string report = hba::test::readText(dir / "BENCHMARKS.md");
  const auto begin = report.find("<!-- benchmark-harness:begin -->");
  ASSERT_NE(begin, std::string::npos) << report;
  EXPECT_GT(begin, report.find("Intro.")) << "the section goes after the introduction";
  EXPECT_LT(report.find("<!-- benchmark-harness:end -->"), report.find("## Hand-written"));
  EXPECT_NE(report.find("keep me"), std::string::npos);
  EXPECT_NE(report.find("| `sim-livox-100-drift` | 100 | 1 |"), std::string::npos) << report;
  EXPECT_TRUE(fs::is_regular_file(dir / "results" / "results.json"));
}

TEST(BenchmarkHarness, FailsLoudlyWhenOptimizedPosesAreWorseThanTheInitialOnes) {
  if (!pythonAvailable()) GTEST_SKIP() << "python3 is not installed";
  hba::test::TempDir dir;
  const auto run = runHarness(dir, HBA_SOURCE_DIR "/tests/bench/corrupting_hba.sh",
                              "HBA_REAL_TOOL=" + hba::test::cliPath().string());
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("ACCURACY REGRESSION: sim-livox-100-drift ATE"), std::string::npos) << run.output;
  // The results are written all the same, with the row marked.
  const std::string report = hba::test::readText(dir / "BENCHMARKS.md");
  EXPECT_NE(report.find("ACCURACY REGRESSION**"), std::string::npos) << report;
  EXPECT_TRUE(fs::is_regular_file(dir / "results" / "results.json"));
}

// Two builds side by side (scripts/bench/compare_builds.py): here the real
// tool against one that ruins its poses. Both are timed in one sitting, the
// table gives the ratios, and the broken build's accuracy shows in it.
TEST(BenchmarkHarness, ComparesTwoBuildsInOneSitting) {
  if (!pythonAvailable()) GTEST_SKIP() << "python3 is not installed";
  hba::test::TempDir dir;
  const auto run = runCommand("env HBA_REAL_TOOL=" + hba::test::cliPath().string() +
                              " python3 " HBA_SOURCE_DIR
                              "/scripts/bench/compare_builds.py --only sim-livox-100-drift"
                              " --runs 2 --render --jobs 1 --hba-a " +
                              hba::test::cliPath().string() +
                              " --hba-b " HBA_SOURCE_DIR
                              "/tests/bench/corrupting_hba.sh --label-a good --label-b broken"
                              " --io-floor " HBA_IO_FLOOR_PATH " --data-dir " +
                              (dir / "data").string() + " --output " + (dir / "compare.md").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string table = hba::test::readText(dir / "compare.md");
  EXPECT_NE(table.find("| `sim-livox-100-drift` | 100 |"), std::string::npos) << table;
  EXPECT_NE(table.find("broken/good"), std::string::npos) << table;
  EXPECT_NE(table.find("picture / no picture"), std::string::npos) << table;
  const std::string raw = hba::test::readText(dir / "compare.json");
  // Two runs of each build, interleaved, and the broken build's error far larger.
  const auto json = nlohmann::json::parse(raw);
  const auto& record = json["records"]["sim-livox-100-drift"]["builds"];
  ASSERT_EQ(record["good"]["runs"].size(), 2u);
  ASSERT_EQ(record["broken"]["runs"].size(), 2u);
  EXPECT_GT(record["broken"]["runs"][0]["ate_m"].get<double>(),
            10.0 * record["good"]["runs"][0]["ate_m"].get<double>());
}

}  // namespace
