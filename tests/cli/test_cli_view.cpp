// `hba view` and the report page `hba optimize` writes: OUT/report.html by
// default (not with --no-report-page), written again by `hba view OUT`, a
// page for a dataset and a pose file with -o; a file hba did not write is
// replaced only with --force, and bad input is refused with its name.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }
std::string hba() { return quoted(test::cliPath()); }
bool isPage(const fs::path& file) {
  return test::readText(file).rfind("<!DOCTYPE html>\n<!-- hba report page", 0) == 0;
}

class View : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new test::TempDir;
    const test::CommandResult sim =
        test::runCommand(hba() + " -q simulate --frames 60 --seed 5 -o " + quoted(*dir / "sim"));
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    const test::CommandResult run = test::runCommand(hba() + " -q optimize " + quoted(*dir / "sim") + " -o " +
                                                     quoted(*dir / "out") + " --layers 1 --no-render");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete dir; }
  static test::CommandResult view(const std::string& arguments) {
    return test::runCommand(hba() + " view " + arguments);
  }
  static test::TempDir* dir;
};
test::TempDir* View::dir = nullptr;

TEST_F(View, OptimizeWritesThePageUnlessTold) {
  EXPECT_TRUE(isPage(*dir / "out" / "report.html"));
  const test::CommandResult run =
      test::runCommand(hba() + " -q optimize " + quoted(*dir / "sim") + " -o " + quoted(*dir / "out-nopage") +
                       " --layers 1 --no-render --no-report-page");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(*dir / "out-nopage" / "pose.json"));
  EXPECT_FALSE(fs::exists(*dir / "out-nopage" / "report.html"));
}

TEST_F(View, OutputFolderGetsItsPageAgainWithoutForce) {
  const fs::path page = *dir / "out" / "report.html";
  const std::string before = test::readText(page);
  fs::remove(page);
  const test::CommandResult first = view(quoted(*dir / "out"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(test::readText(page) == before) << "the same page as optimize wrote";
  const test::CommandResult again = view(quoted(*dir / "out") + " --points 5000");
  ASSERT_EQ(again.exit_code, 0) << again.output << " (an hba page is replaced without --force)";
  EXPECT_LT(fs::file_size(page), before.size());
  EXPECT_NE(again.output.find("report.html"), std::string::npos) << again.output;
}

TEST_F(View, AFileHbaDidNotWriteIsReplacedOnlyWithForce) {
  fs::create_directories(*dir / "mine");
  const fs::path mine = *dir / "mine" / "page.html";
  test::writeText(mine, "<html>my notes</html>");
  const std::string base =
      quoted(*dir / "sim") + " --compare " + quoted(*dir / "out" / "pose.json") + " -o " + quoted(mine);
  const test::CommandResult refused = view(base);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
  EXPECT_EQ(test::readText(mine), "<html>my notes</html>");
  const test::CommandResult forced = view(base + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_TRUE(isPage(mine));
}

TEST_F(View, BadInputIsRefusedByName) {
  // A dataset needs -o; a page is .html; a pose file must have one pose per scan.
  const test::CommandResult no_output = view(quoted(*dir / "sim"));
  EXPECT_NE(no_output.exit_code, 0);
  EXPECT_NE(no_output.output.find("-o page.html"), std::string::npos) << no_output.output;
  const test::CommandResult png = view(quoted(*dir / "sim") + " -o " + quoted(*dir / "page.png"));
  EXPECT_NE(png.exit_code, 0);
  EXPECT_NE(png.output.find("must be an .html file"), std::string::npos) << png.output;
  test::writeText(*dir / "short.txt", "0 0 0 0 0 0 1\n0 0 0 0 0 0 1\n0 0 0 0 0 0 1\n");
  const test::CommandResult short_poses = view(quoted(*dir / "sim") + " --compare " +
                                               quoted(*dir / "short.txt") + " -o " + quoted(*dir / "p.html"));
  EXPECT_NE(short_poses.exit_code, 0);
  EXPECT_NE(short_poses.output.find("short.txt"), std::string::npos) << short_poses.output;
  EXPECT_NE(short_poses.output.find("3 poses for 60 scans"), std::string::npos) << short_poses.output;
  EXPECT_FALSE(fs::exists(*dir / "p.html"));
  // Asked for with --gt, a ground truth of the wrong length is refused too.
  const test::CommandResult short_gt =
      view(quoted(*dir / "sim") + " --gt " + quoted(*dir / "short.txt") + " -o " + quoted(*dir / "p.html"));
  EXPECT_NE(short_gt.exit_code, 0);
  EXPECT_NE(short_gt.output.find("3 poses for 60 scans"), std::string::npos) << short_gt.output;
  // A gt.txt beside the data that does not pair up is left out with a warning, as by hba optimize.
  fs::copy(*dir / "sim", *dir / "sim-bad-gt", fs::copy_options::recursive);
  fs::copy_file(*dir / "short.txt", *dir / "sim-bad-gt" / "gt.txt", fs::copy_options::overwrite_existing);
  const test::CommandResult beside =
      view(quoted(*dir / "sim-bad-gt") + " -o " + quoted(*dir / "bad-gt.html"));
  EXPECT_EQ(beside.exit_code, 0) << beside.output;
  EXPECT_NE(beside.output.find("not drawn"), std::string::npos) << beside.output;
  // Never into the input.
  const test::CommandResult inside = view(quoted(*dir / "sim") + " -o " + quoted(*dir / "sim" / "page.html"));
  EXPECT_NE(inside.exit_code, 0);
  EXPECT_FALSE(fs::exists(*dir / "sim" / "page.html"));
  // A report that does not name its dataset.
  fs::create_directories(*dir / "broken");
  test::writeText(*dir / "broken" / "report.json", "{\"input\": {}}");
  fs::copy_file(*dir / "out" / "pose.json", *dir / "broken" / "pose.json");
  const test::CommandResult broken = view(quoted(*dir / "broken"));
  EXPECT_NE(broken.exit_code, 0);
  EXPECT_NE(broken.output.find("report.json: has no input.dataset"), std::string::npos) << broken.output;
}

// Issue 57 items 16 and 20: a report.json naming a moved dataset, or none,
// said "dataset folder not found" without saying the path came from it.
TEST_F(View, AReportNamingAMovedOrNoDatasetSaysSo) {
  nlohmann::json report = nlohmann::json::parse(test::readText(*dir / "out" / "report.json"));
  for (const std::string& dataset : {std::string("/nonexistent/moved-sim"), std::string()}) {
    const fs::path out = *dir / (dataset.empty() ? "out-no-dataset" : "out-moved");
    fs::create_directories(out);
    fs::copy_file(*dir / "out" / "pose.json", out / "pose.json", fs::copy_options::overwrite_existing);
    report["input"]["dataset"] = dataset;
    test::writeText(out / "report.json", report.dump(2));
    const std::string expected =
        dataset.empty() ? (out / "report.json").string() + ": input.dataset is empty"
                        : (out / "report.json").string() + ": names " + dataset +
                              " as the run's input.dataset, which is not there (moved or deleted?)";
    const test::CommandResult viewed = view(quoted(out));
    EXPECT_EQ(viewed.exit_code, 1) << viewed.output;
    EXPECT_NE(viewed.output.find(expected), std::string::npos) << viewed.output;
    EXPECT_FALSE(fs::exists(out / "report.html"));
    const test::CommandResult mapped =
        test::runCommand(hba() + " -q optimize " + quoted(*dir / "sim") + " --map " + quoted(out) + " -o " +
                         quoted(*dir / "never"));
    EXPECT_EQ(mapped.exit_code, 1) << mapped.output;
    EXPECT_NE(mapped.output.find(expected), std::string::npos) << mapped.output;
    EXPECT_FALSE(fs::exists(*dir / "never"));
  }
}

// A report.json whose input.scans_in_world is not true or false (seen in
// writing fuzz_report_json): refused naming the file and the field, not with
// the JSON library's "unexpected failure: ... type must be boolean".
TEST_F(View, AReportWithAFlagOfAnotherTypeIsRefusedByName) {
  fs::create_directories(*dir / "odd-flag");
  std::string report = test::readText(*dir / "out" / "report.json");
  const std::string flag = "\"scans_in_world\": false";
  const std::size_t at = report.find(flag);
  ASSERT_NE(at, std::string::npos) << report;
  report.replace(at, flag.size(), "\"scans_in_world\": \"yes\"");
  test::writeText(*dir / "odd-flag" / "report.json", report);
  fs::copy_file(*dir / "out" / "pose.json", *dir / "odd-flag" / "pose.json");
  const test::CommandResult odd = view(quoted(*dir / "odd-flag"));
  EXPECT_EQ(odd.exit_code, 1) << odd.output;
  EXPECT_NE(odd.output.find("report.json: input.scans_in_world is a string, not true or false"),
            std::string::npos)
      << odd.output;
  EXPECT_FALSE(fs::exists(*dir / "odd-flag" / "report.html"));
  // hba optimize --map OUT reads the same report.
  const test::CommandResult map =
      test::runCommand(hba() + " optimize " + quoted(*dir / "sim") + " --map " + quoted(*dir / "odd-flag") +
                       " -o " + quoted(*dir / "odd-map-out") + " --layers 1 --no-render");
  EXPECT_EQ(map.exit_code, 1) << map.output;
  EXPECT_NE(map.output.find("report.json: input.scans_in_world is a string, not true or false"),
            std::string::npos)
      << map.output;
  EXPECT_FALSE(fs::exists(*dir / "odd-map-out"));
}

}  // namespace
}  // namespace hba
