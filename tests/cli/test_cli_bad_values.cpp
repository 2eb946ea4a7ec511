// Every bad value of every numeric flag is a usage error: exit 2, before any
// work, with a message that names the flag as typed and the range it takes
// (docs/cli.md). Also the same for a --config file's values.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_runs.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

struct BadValue {
  std::string command;  // the hba arguments before the bad flag (DATA, OUT stand for folders)
  std::string flag;     // the flag and its value
  std::string says;     // besides the flag's name, the message holds this
};

// One row per flag and kind of bad value: negative, zero where a size must be
// positive, inf, nan, overflow, absurd, malformed.
const std::vector<BadValue> kRows = {
    {"-q", "-j -1", "0 (all cores) or [1, 4096]"},
    {"-q", "-j 99999999999999999999", "(too large)"},
    {"-q", "-j 2.5", "not a whole number"},
    {"mme DATA", "--radius inf", "must be (0, 10] m, got inf (not finite)"},
    {"mme DATA", "--radius nan", "(not finite)"},
    {"mme DATA", "--radius 0", "must be (0, 10] m"},
    {"mme DATA", "--radius -1", "must be (0, 10] m"},
    {"mme DATA", "--radius 1e400", "(too large)"},
    {"mme DATA", "--radius 100", "(too large)"},
    {"mme DATA", "--voxel -1", "0 (keep every point) or [0.001, 100] m"},
    {"mme DATA", "--voxel inf", "(not finite)"},
    {"mme DATA", "--voxel 1e-9", "[0.001, 100] m"},
    {"mme DATA", "--min-neighbors -1", "[0, 1000000]"},
    {"mme DATA", "--min-neighbors 2.5", "not a whole number"},
    {"mme DATA", "--min-neighbors 99999999999999999999", "(too large)"},
    {"map DATA -o OUT/m.pcd", "--voxel -1", "0 (keep every point) or [0.001, 100] m"},
    {"map DATA -o OUT/m.pcd", "--voxel nan", "(not finite)"},
    {"render DATA -o OUT/m.png", "--crop 1,2,3", "expected xmin,ymin,xmax,ymax"},
    {"render DATA -o OUT/m.png", "--crop 3,0,1,1", "is empty"},
    {"render DATA -o OUT/m.png", "--width 100", "[200, 16384] px"},
    {"render DATA -o OUT/m.png", "--height 1e9", "(too large)"},
    {"render DATA -o OUT/m.png", "--voxel inf", "(not finite)"},
    {"simulate -o OUT/sim", "--seed -5", "[0, 18446744073709551615]"},
    {"simulate -o OUT/sim", "--seed 99999999999999999999", "(too large)"},
    {"simulate -o OUT/sim", "--speed -5", "(0, 100] m/s"},
    {"simulate -o OUT/sim", "--speed inf", "(not finite)"},
    {"simulate -o OUT/sim", "--speed 101", "(too large)"},
    {"simulate -o OUT/sim", "--frames 0", "[1, 1000000]"},
    {"simulate -o OUT/sim", "--frames -1", "[1, 1000000]"},
    {"simulate -o OUT/sim", "--frames 1e12", "(too large)"},
    {"simulate -o OUT/sim", "--noise 2", "[0, 1] m"},
    {"simulate -o OUT/sim", "--dropout 1", "[0, 1)"},
    {"simulate -o OUT/sim", "--max-range nan", "(not finite)"},
    {"simulate -o OUT/sim", "--drift-translation -0.1", "[0, 1]"},
    {"simulate -o OUT/sim", "--drift-rotation 20", "[0, 10] deg per m"},
    {"simulate -o OUT/sim", "--drift-z inf", "(not finite)"},
    {"simulate -o OUT/sim", "--jitter-translation 2", "[0, 1] m"},
    {"simulate -o OUT/sim", "--jitter-rotation -1", "[0, 10] deg"},
    {"simulate -o OUT/sim", "--downsample -1", "0 (keep every return)"},
    {"simulate -o OUT/sim", "--progress-every -1", "0 (at the end only)"},
    {"simulate -o OUT/sim", "--sessions 0", "[1, 1000]"},
    {"simulate -o OUT/sim", "--session-shift -1", "[0, 100000] m"},
    {"simulate -o OUT/sim", "--session-frames 0", "[1, 1000000]"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--t-max-diff -1", "[0, 3600] s"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--t-max-diff inf", "(not finite)"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--min-matched 2", "[0, 1]"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--delta 0", "(0, 1000000]"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--delta nan", "(not finite)"},
    {"eval --gt DATA/gt.txt --est DATA/gt.txt", "--delta 2.5", "whole number"},
    {"info DATA", "--sample -1", "0 (all) or [1, 1000000000]"},
    {"info DATA", "--sample 1.5", "not a whole number"},
    {"optimize DATA -o OUT/o", "--window -3", "must be 0 (automatic) or >= 2, got -3"},
    {"optimize DATA -o OUT/o", "--window 99999999999999999999", "(too large: at most 2147483647)"},
    {"optimize DATA -o OUT/o", "--window 2.5", "not a whole number"},
    {"optimize DATA -o OUT/o", "--voxel -1", "must be [0.01, 100], got -1"},
    {"optimize DATA -o OUT/o", "--voxel 500", "(too large)"},
    {"optimize DATA -o OUT/o", "--voxel inf", "(not finite)"},
    {"optimize DATA -o OUT/o", "--stride -1", "0 (half the window) or >= 1"},
    {"optimize DATA -o OUT/o", "--stride 10 --window 10", "stride must be below window"},
    {"optimize DATA -o OUT/o", "--iterations 100000", "must be [1, 100], got 100000 (too large)"},
    {"optimize DATA -o OUT/o", "--iterations 0", "[1, 100]"},
    {"optimize DATA -o OUT/o", "--settle-translation 0", "[1e-06, 1]"},
    {"optimize DATA -o OUT/o", "--theta-local 1", "(0, 1)"},
    {"optimize DATA -o OUT/o", "--downsample-scans nan", "(not finite)"},
    {"optimize DATA -o OUT/o", "--scan-voxel -1", "0 (off) or [0.001, 100]"},
    {"optimize DATA -o OUT/o", "--layers -1", "0 (automatic) or >= 1"},
    {"optimize DATA -o OUT/o", "--point-sigma 0", "> 0"},
    {"optimize DATA -o OUT/o", "--refine-voxel inf", "(not finite)"},
    {"optimize DATA -o OUT/o", "--revisit-drift 2", "[0, 1]"},
    {"optimize DATA -o OUT/o", "--ba-iterations -1", ">= 0"},
    {"optimize DATA -o OUT/o", "--reject 1", "[0, 1)"},
    {"optimize DATA -o OUT/o", "--prior-max-gap inf", "(0, 3600] s"},
    {"optimize DATA -o OUT/o", "--prior-max-gap 0", "(0, 3600] s"},
    {"optimize DATA -o OUT/o", "--extrinsic 1,2,3", "expected 7 numbers"},
    {"optimize DATA DATA -o OUT/o", "--align regster", "must be register, identity, or a file of transforms"},
    {"simulate -o OUT/sim", "--trajectory blok", "must be block, figure8, street, or a trajectory file"},
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

class CliBadValues : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    ASSERT_EQ(test::runHba("-q simulate --frames 12 --seed 1 -o " + test::quoted(*dir_ / "data")).exit_code,
              0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string arguments(const std::string& text) {
    return replaced(replaced(text, "DATA", test::quoted(*dir_ / "data")), "OUT", test::quoted(*dir_ / "out"));
  }
  static test::TempDir* dir_;
};
test::TempDir* CliBadValues::dir_ = nullptr;

TEST_F(CliBadValues, EveryNumericFlagRefusesBadValuesAsUsage) {
  for (const BadValue& row : kRows) {
    const std::string flag = row.flag.substr(0, row.flag.find(' '));
    // The flag before or after the command's own arguments alike.
    const std::string line = row.command == "-q" ? row.flag + " info " + arguments("DATA")
                                                 : arguments(row.command) + " " + row.flag;
    const test::CommandResult run = test::runHba(line);
    EXPECT_EQ(run.exit_code, 2) << "hba " << line << "\n" << run.output;
    const std::string name = flag == "-j" ? "--threads" : flag;
    EXPECT_NE(run.output.find(name), std::string::npos)
        << "hba " << line << " does not name " << name << ":\n"
        << run.output;
    EXPECT_NE(run.output.find(row.says), std::string::npos)
        << "hba " << line << " does not say '" << row.says << "':\n"
        << run.output;
  }
  EXPECT_FALSE(fs::exists(*dir_ / "out")) << "a refused run wrote something";
}

// A --config file's bad values are usage errors too, naming the file and key.
TEST_F(CliBadValues, ConfigFileValuesAreUsageErrors) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"window: -3\n", "setting window must be 0 (automatic) or >= 2, got -3"},
      {"voxel: .inf\n", "setting voxel must be [0.01, 100]"},
      {"iterations: 100000\n", "setting iterations must be [1, 100], got 100000 (too large)"},
      {"window: 99999999999999999999\n", "(too large: at most 2147483647)"},
      {"local:\n  eigen_ratio: 1.5\n", "setting local.eigen_ratio must be (0, 1)"},
      {"windw: 10\n", "unknown setting 'windw' (did you mean 'window'?)"},
      {"window: [1, 2]\n", "'window' has a value of the wrong type"},
      {"window: 10\nstride: 4\nwindow: 12\n", "'window' is given twice (lines 1 and 3); give it once"},
      {"local:\n  voxel_size: 2\n  voxel_size: 3\n", "'local.voxel_size' is given twice (lines 2 and 3)"},
      {"window: [\n", "not valid YAML"},
  };
  int index = 0;
  for (const auto& [yaml, says] : files) {
    const fs::path file = *dir_ / ("bad" + std::to_string(index++) + ".yaml");
    test::writeText(file, yaml);
    const test::CommandResult run =
        test::runHba("optimize --config " + test::quoted(file) + " " + arguments("DATA -o OUT/o"));
    EXPECT_EQ(run.exit_code, 2) << yaml << run.output;
    EXPECT_NE(run.output.find(file.string() + ": "), std::string::npos) << yaml << run.output;
    EXPECT_NE(run.output.find(says), std::string::npos) << "'" << says << "' not in:\n" << run.output;
  }
  // What settings hold together is checked once the flags are in too: the
  // message names both flags (a file's stride may fit a flag's --window).
  test::writeText(*dir_ / "stride.yaml", "stride: 12\n");
  const test::CommandResult run = test::runHba("optimize --config " + test::quoted(*dir_ / "stride.yaml") +
                                               " " + arguments("DATA -o OUT/o") + " --window 10");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("setting stride must be below window (--stride 12 >= --window 10)"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(*dir_ / "out"));
}

}  // namespace
}  // namespace hba
