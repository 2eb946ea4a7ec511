// The tool behaves like the command-line tools users know: results on
// stdout and logs on stderr, exit codes 0 / 1 / 2, "did you mean" for
// mistyped commands, flags and settings, help when run alone, a log file.
#include <gtest/gtest.h>

#include <string>

#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

struct SplitResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `hba <arguments>` with stdout and stderr captured apart.
SplitResult runSplit(const std::string& arguments, const test::TempDir& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  // A group, so that runCommand's own "2>&1" applies to nothing.
  const test::CommandResult run = test::runCommand("{ " + quoted(test::cliPath()) + " " + arguments + " > " +
                                                   quoted(out) + " 2> " + quoted(err) + "; }");
  return {run.exit_code, test::readText(out), test::readText(err)};
}

void expectContains(const std::string& text, const std::string& piece) {
  EXPECT_NE(text.find(piece), std::string::npos) << "'" << piece << "' not in:\n" << text;
}

class CliConventions : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(runSplit("-q simulate --frames 8 --seed 1 -o " + quoted(dir / "sim"), dir).exit_code, 0);
  }
  test::TempDir dir;
};

TEST_F(CliConventions, ResultsOnStdoutLogsOnStderr) {
  const SplitResult mme = runSplit("mme " + quoted(dir / "sim"), dir);
  ASSERT_EQ(mme.exit_code, 0) << mme.err;
  EXPECT_EQ(mme.out.rfind("MME ", 0), 0u) << mme.out;
  EXPECT_EQ(mme.out.find("[info]"), std::string::npos) << mme.out;
  expectContains(mme.err, "[info] merging 8 scans");
  const SplitResult missing = runSplit("mme " + quoted(dir / "nowhere"), dir);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_TRUE(missing.out.empty()) << missing.out;
  expectContains(missing.err, "[error]");
  expectContains(missing.err, "nowhere");
}

TEST_F(CliConventions, ExitCodesAreZeroOneTwo) {
  EXPECT_EQ(runSplit("--help", dir).exit_code, 0);
  EXPECT_EQ(runSplit("--version", dir).exit_code, 0);
  EXPECT_EQ(runSplit("optimize --help", dir).exit_code, 0);
  EXPECT_EQ(runSplit("info " + quoted(dir / "nowhere"), dir).exit_code, 1);  // bad input
  EXPECT_EQ(
      runSplit("map " + quoted(dir / "sim") + " -o " + quoted(dir / "m.pcd") + " --voxel -1", dir).exit_code,
      2);
  EXPECT_EQ(runSplit("eval --gt", dir).exit_code, 2);    // missing value
  EXPECT_EQ(runSplit("info", dir).exit_code, 2);         // missing DIR
  EXPECT_EQ(runSplit("-j x info .", dir).exit_code, 2);  // not a number
}

// The entropy stage of hba mme reports its progress too (8.8 s at radius 1
// on hku1; minutes at a few metres). HBA_PROGRESS_SECONDS=0: a line at every
// report, one per 0.1 s; the stage takes over a second here.
TEST_F(CliConventions, MmeEntropyReportsItsProgress) {
  const test::CommandResult run = test::runCommand("HBA_PROGRESS_SECONDS=0 " + quoted(test::cliPath()) +
                                                   " mme " + quoted(dir / "sim") + " --radius 1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  expectContains(run.output, "[info] map entropy: ");
  expectContains(run.output, " points/s, ETA ");
}

TEST_F(CliConventions, AloneItPrintsTheHelp) {
  const SplitResult alone = runSplit("", dir);
  EXPECT_EQ(alone.exit_code, 0);
  expectContains(alone.out, "Usage: hba [OPTIONS] SUBCOMMAND");
  expectContains(alone.out, "optimize");
  expectContains(alone.out, "Exit codes: 0 success, 1 failure");
}

TEST_F(CliConventions, MistypedCommandsAndFlagsGetASuggestion) {
  const SplitResult command = runSplit("optimze " + quoted(dir / "sim"), dir);
  EXPECT_EQ(command.exit_code, 2);
  expectContains(command.err, "'optimze' is not an hba command (did you mean 'optimize'?)");
  const SplitResult flag =
      runSplit("optimize " + quoted(dir / "sim") + " -o " + quoted(dir / "o") + " --windw 20", dir);
  EXPECT_EQ(flag.exit_code, 2);
  expectContains(flag.err, "'--windw' is not a flag here (did you mean '--window'?)");
  EXPECT_FALSE(fs::exists(dir / "o"));
  const SplitResult global = runSplit("--quite info " + quoted(dir / "sim"), dir);
  EXPECT_EQ(global.exit_code, 2);
  expectContains(global.err, "did you mean '--quiet'?");
}

TEST_F(CliConventions, MistypedSettingGetsASuggestionAndTheValidNames) {
  test::writeText(dir / "bad.yaml", "windw: 12\n");
  const SplitResult run = runSplit("optimize " + quoted(dir / "sim") + " -o " + quoted(dir / "o") +
                                       " --config " + quoted(dir / "bad.yaml"),
                                   dir);
  EXPECT_EQ(run.exit_code, 2);  // usage, as a mistyped flag
  expectContains(run.err, "unknown setting 'windw' (did you mean 'window'?)");
  expectContains(run.err, "stride");
}

// --print-config writes a complete, commented file that --config reads back.
TEST_F(CliConventions, PrintedConfigRoundTrips) {
  const SplitResult printed = runSplit("optimize --print-config --window 12 --no-refine", dir);
  ASSERT_EQ(printed.exit_code, 0) << printed.err;
  expectContains(printed.out, "window: 12");
  expectContains(printed.out, "refine: false");
  expectContains(printed.out,
                 "# frames per local window, w; automatic: the scans of 150 000 points, at least 10; 0 = "
                 "automatic (--window)");
  test::writeText(dir / "settings.yaml", printed.out);
  const SplitResult again =
      runSplit("optimize --print-config --config " + quoted(dir / "settings.yaml"), dir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.out, printed.out);
  EXPECT_EQ(runSplit("optimize " + quoted(dir / "sim"), dir).exit_code, 2);  // -o is still required
}

TEST_F(CliConventions, LogFileGetsEveryMessageWithTimes) {
  const SplitResult run =
      runSplit("-q --log-file " + quoted(dir / "hba.log") + " mme " + quoted(dir / "sim"), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;  // -q: no info on the console
  const std::string log = test::readText(dir / "hba.log");
  expectContains(log, "[info] merging 8 scans");
  EXPECT_EQ(log.front(), '[');  // "[2026-11-22 21:30:00.123] [info] ..."
  test::writeText(dir / "a_file", "");
  const SplitResult unwritable =
      runSplit("--log-file " + quoted(dir / "a_file" / "hba.log") + " mme " + quoted(dir / "sim"), dir);
  EXPECT_EQ(unwritable.exit_code, 1);
  expectContains(unwritable.err, "--log-file: the folder");
}

}  // namespace
}  // namespace hba

namespace hba {
namespace {

// Not a terminal: plain progress lines with the count, the rate and the ETA.
TEST(CliProgress, PlainLinesWhenNotATerminal) {
  test::TempDir dir;
  ASSERT_EQ(runSplit("-q simulate --frames 80 --seed 2 -o " + quoted(dir / "sim"), dir).exit_code, 0);
  const SplitResult run =
      runSplit("optimize " + quoted(dir / "sim") + " -o " + quoted(dir / "out") + " --no-render", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err.find('\r'), std::string::npos) << "no bar outside a terminal";
  // HBA_PROGRESS_SECONDS=0 (below): a line at every report.
  const std::string frequent = "HBA_PROGRESS_SECONDS=0 ";
  const test::CommandResult lines =
      test::runCommand(frequent + quoted(test::cliPath()) + " optimize " + quoted(dir / "sim") + " -o " +
                       quoted(dir / "out2") + " --no-render");
  ASSERT_EQ(lines.exit_code, 0) << lines.output;
  expectContains(lines.output, "[info] layer 1: ");
  expectContains(lines.output, "/15 windows (");
  expectContains(lines.output, "windows/s, ETA ");
}

}  // namespace
}  // namespace hba
