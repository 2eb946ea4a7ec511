// `hba eval` end to end: real trajectories against an independent reference,
// and the demo's pairing of a stamped TUM file with an unstamped pose.json.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "test_support.hpp"

namespace hba::test {
namespace {

// Printed by `python3 tests/eval/evo_reference.py optimized_poses.txt
// odom_poses.txt <align> 1` (numpy, written independently of the C++):
// rmse, mean, median, max of ATE trans, ATE rot, RPE trans, RPE rot.
struct Reference {
  const char* align;
  double values[4][4];
};
const Reference kHku1[] = {
    {"se3",
     {{0.082294867, 0.065309501, 0.039567863, 0.181163212},
      {0.457590945, 0.444872860, 0.405429759, 0.663565841},
      {0.001289281, 0.001070435, 0.000845081, 0.004434869},
      {0.005096679, 0.003554434, 0.002290808, 0.019107831}}},
    {"sim3",
     {{0.082176212, 0.065064039, 0.040878480, 0.186104815},
      {0.457590945, 0.444872860, 0.405429759, 0.663565841},
      {0.001291151, 0.001083029, 0.000904930, 0.004352082},
      {0.005096679, 0.003554434, 0.002290808, 0.019107831}}},
    {"none",
     {{0.172619160, 0.142044979, 0.119731772, 0.327358281},
      {0.337750029, 0.299918066, 0.375418354, 0.445068757},
      {0.001289281, 0.001070435, 0.000845081, 0.004434869},
      {0.005096679, 0.003554434, 0.002290808, 0.019107831}}},
};

TEST(EvalCli, Hku1AgreesWithIndependentNumpyReference) {
  const auto hku1 = sharedDataDir() / "hku1";
  if (!std::filesystem::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "no " << hku1;
  TempDir tmp;
  for (const Reference& ref : kHku1) {
    const auto json_path = tmp / (std::string(ref.align) + ".json");
    const CommandResult run = runCommand(
        cliPath().string() + " eval --gt " + (hku1 / "optimized_poses.txt").string() + " --est " +
        (hku1 / "odom_poses.txt").string() + " --align " + ref.align + " --json " + json_path.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto json = nlohmann::json::parse(readText(json_path));
    EXPECT_EQ(json["matched"], 314);
    const nlohmann::json* blocks[4] = {&json["ate"]["translation_m"], &json["ate"]["rotation_deg"],
                                       &json["rpe"]["translation_m"], &json["rpe"]["rotation_deg"]};
    const char* stats[4] = {"rmse", "mean", "median", "max"};
    for (int b = 0; b < 4; ++b) {
      for (int s = 0; s < 4; ++s) {
        EXPECT_NEAR((*blocks[b])[stats[s]].get<double>(), ref.values[b][s], 1e-6)
            << ref.align << " block " << b << " " << stats[s];
      }
    }
  }
}

TEST(EvalCli, StampedTumAgainstUnstampedHbaPairsByIndexAndPrintsTheLabel) {
  TempDir tmp;
  std::string tum, hba;
  for (int i = 0; i < 6; ++i) {
    // Ground truth along a curve; the estimate 3 m off (1, 2, 2), unrotated.
    const double x = i, y = 0.1 * i * i, z = 0.2 * i;
    tum += std::to_string(1000.0 + 0.1 * i) + " " + std::to_string(x) + " " + std::to_string(y) + " " +
           std::to_string(z) + " 0 0 0 1\n";
    hba += std::to_string(x + 1) + " " + std::to_string(y + 2) + " " + std::to_string(z + 2) + " 1 0 0 0\n";
  }
  writeText(tmp / "gt.txt", tum);
  writeText(tmp / "pose.json", hba);
  const std::string base = cliPath().string() + " eval --gt " + (tmp / "gt.txt").string() + " --est " +
                           (tmp / "pose.json").string();
  const CommandResult none = runCommand(base + " --align none --label before");
  ASSERT_EQ(none.exit_code, 0) << none.output;
  EXPECT_EQ(none.output.rfind("before  6 of 6 estimated poses matched by index", 0), 0u) << none.output;
  EXPECT_TRUE(std::regex_search(
      none.output,
      std::regex("\nbefore  ATE trans m +3.000000 +3.000000 +3.000000 +0.000000 +3.000000 +3.000000\n")))
      << none.output;
  const CommandResult se3 = runCommand(base + " --label after");
  ASSERT_EQ(se3.exit_code, 0) << se3.output;
  EXPECT_TRUE(std::regex_search(se3.output, std::regex("\nafter  ATE trans m +0.000000 "))) << se3.output;
}

// No stamp within the tolerance (docs/eval.md): both files named with their
// stamps' counts and ranges, the tolerance, and the flag that would pair them.
TEST(EvalCli, StampsThatMatchNowhereAreShownWithBothRanges) {
  TempDir tmp;
  std::string gt, est;
  for (int i = 0; i < 4; ++i) {
    gt += std::to_string(1000 + i) + " " + std::to_string(i) + " 0 0 0 0 0 1\n";
    est += std::to_string(i) + " " + std::to_string(i) + " 0 0 0 0 0 1\n";
  }
  writeText(tmp / "gt.tum", gt);
  writeText(tmp / "est.tum", est);
  const std::string base = cliPath().string() + " eval --gt " + (tmp / "gt.tum").string() + " --est ";
  const CommandResult same_count = runCommand(base + (tmp / "est.tum").string());
  EXPECT_EQ(same_count.exit_code, 1);
  for (const std::string& piece :
       std::vector<std::string>{"only 0 of 4 estimated poses (0 %) have a ground-truth pose within 0.01 s",
                                (tmp / "gt.tum").string() + " holds 4 stamps from 1000.000 to 1003.000 s",
                                (tmp / "est.tum").string() + " holds 4 stamps from 0.000 to 3.000 s",
                                "--assoc index: both files hold 4 poses"}) {
    EXPECT_NE(same_count.output.find(piece), std::string::npos) << piece << "\n" << same_count.output;
  }
  writeText(tmp / "est.tum", est.substr(0, est.rfind('\n', est.size() - 2) + 1));  // 3 poses
  const CommandResult other_count = runCommand(base + (tmp / "est.tum").string());
  EXPECT_EQ(other_count.exit_code, 1);
  EXPECT_NE(other_count.output.find("holds 3 stamps from 0.000 to 2.000 s"), std::string::npos)
      << other_count.output;
  EXPECT_NE(other_count.output.find("widen the tolerance (--t-max-diff"), std::string::npos)
      << other_count.output;
  EXPECT_NE(other_count.output.find("not 3 and 4"), std::string::npos) << other_count.output;
}

TEST(EvalCli, ReportsProblemsInsteadOfGuessing) {
  TempDir tmp;
  writeText(tmp / "a.txt", "0 0 0 1 0 0 0\n1 0 0 1 0 0 0\n2 0 0 1 0 0 0\n");
  writeText(tmp / "b.txt", "0 0 0 1 0 0 0\n1 0 0 1 0 0 0\n");
  const std::string base = cliPath().string() + " eval --gt " + (tmp / "a.txt").string();
  const CommandResult counts = runCommand(base + " --est " + (tmp / "b.txt").string());
  EXPECT_NE(counts.exit_code, 0);
  EXPECT_NE(counts.output.find("equal pose counts"), std::string::npos) << counts.output;
  const CommandResult time = runCommand(base + " --est " + (tmp / "a.txt").string() + " --assoc time");
  EXPECT_NE(time.exit_code, 0);
  EXPECT_NE(time.output.find("timestamps"), std::string::npos) << time.output;
}

}  // namespace
}  // namespace hba::test

namespace hba::test {
namespace {

// Big-endian uint32 at `offset` of a file's bytes (PNG header fields).
std::uint32_t bigEndian(const std::string& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = value << 8 | static_cast<unsigned char>(bytes[offset + i]);
  return value;
}

TEST(EvalCli, PlotsTheErrorOverTime) {
  TempDir tmp;
  std::string gt, est;
  for (int i = 0; i < 50; ++i) {
    gt += std::to_string(100.0 + 0.1 * i) + " " + std::to_string(i) + " 0 0 0 0 0 1\n";
    est += std::to_string(100.0 + 0.1 * i) + " " + std::to_string(i) + " " + std::to_string(0.001 * i * i) +
           " 0 0 0 0 1\n";
  }
  writeText(tmp / "gt.txt", gt);
  writeText(tmp / "est.txt", est);
  const std::string base = cliPath().string() + " -q eval --gt " + (tmp / "gt.txt").string() + " --est " +
                           (tmp / "est.txt").string() + " --plot ";
  const CommandResult run = runCommand(base + (tmp / "ate.png").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string png = readText(tmp / "ate.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(bigEndian(png, 16), 1200u);                                   // IHDR width
  EXPECT_EQ(bigEndian(png, 20), 720u);                                    // IHDR height
  EXPECT_NE(runCommand(base + (tmp / "ate.png").string()).exit_code, 0);  // exists: needs --force
  EXPECT_EQ(runCommand(base + (tmp / "ate.png").string() + " --force").exit_code, 0);
  EXPECT_NE(runCommand(base + (tmp / "ate.jpg").string()).exit_code, 0);
}

}  // namespace
}  // namespace hba::test
