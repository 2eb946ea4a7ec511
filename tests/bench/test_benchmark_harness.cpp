// The benchmark harness (scripts/bench) on its smallest quick scenario: an
// honest run passes and fills BENCHMARKS.md's generated section without
// touching the hand-written text; a run whose optimized poses are worse than
// the initial ones fails loudly, so a speed-up can never hide an accuracy loss.
#include <gtest/gtest.h>

#include <string>

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
  return runCommand("env " + environment + " python3 " HBA_SOURCE_DIR "/scripts/bench/run_benchmarks.py --quick"
                    " --only sim-livox-100-drift --jobs 1 --hba " + hba +
                    " --io-floor " HBA_IO_FLOOR_PATH " --data-dir " + (dir / "data").string() +
                    " --output " + (dir / "BENCHMARKS.md").string() +
                    " --results-dir " + (dir / "results").string());
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
  EXPECT_NE(run.output.find("ACCURACY REGRESSION: sim-livox-100-drift ATE"), std::string::npos)
      << run.output;
  // The results are written all the same, with the row marked.
  const std::string report = hba::test::readText(dir / "BENCHMARKS.md");
  EXPECT_NE(report.find("ACCURACY REGRESSION**"), std::string::npos) << report;
  EXPECT_TRUE(fs::is_regular_file(dir / "results" / "results.json"));
}

}  // namespace
