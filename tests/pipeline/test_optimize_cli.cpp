// `hba optimize` end to end on simulated sequences with ground truth: the
// accuracy claims of the method, checked on every CI run (small sizes).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cli_runs.hpp"
#include "hba/ba/global_refinement.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

using test::readJson;
std::string hba() { return test::hbaTool(); }
void run(const std::string& command) { test::runOk(command); }

// ATE translation RMSE (m) of `est` against the simulator's ground truth.
double ateRmse(const fs::path& gt, const fs::path& est, const fs::path& scratch) {
  return test::evalRmse("ate", gt, est, scratch);
}

class OptimizeSimulated : public testing::Test {
 protected:
  test::TempDir dir;
  fs::path data() const { return dir / "sequence"; }
  fs::path out() const { return dir / "result"; }
};

// The stage table's last entry logs every stage's time, in the order they ran.
TEST_F(OptimizeSimulated, LogsTheTimeOfEveryStage) {
  run(hba() + " -q simulate --frames 40 --seed 2 -o " + data().string());
  const test::CommandResult r = test::runCommand(hba() + " optimize " + data().string() + " --no-render -o " +
                                                 out().string() + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t line = r.output.find("stages: closures ");
  ASSERT_NE(line, std::string::npos) << r.output;
  const std::size_t pyramid = r.output.find(" s, pyramid ", line);
  const std::size_t refinement = r.output.find(" s, refinement ", line);
  const std::size_t anchoring = r.output.find(" s, anchoring ", line);
  EXPECT_LT(line, pyramid);
  EXPECT_LT(pyramid, refinement);
  EXPECT_LT(refinement, anchoring);
  EXPECT_NE(anchoring, std::string::npos);
}

TEST_F(OptimizeSimulated, DriftingSequenceGetsFiveTimesMoreAccurate) {
  run(hba() + " -q simulate --frames 120 --seed 5 --drift-translation 0.03 --drift-rotation 0.05 -o " +
      data().string());
  run(hba() + " -q optimize " + data().string() + " -o " + out().string());

  const double before = ateRmse(data() / "gt.txt", data() / "pose.json", dir.path());
  const double after = ateRmse(data() / "gt.txt", out() / "pose.json", dir.path());
  EXPECT_GT(before, 0.1);  // the drift is real
  EXPECT_LT(after, before / 5.0) << "before " << before << " m, after " << after << " m";

  // Every promised output is there and consistent.
  for (const char* name : {"pose.json", "poses_kitti.txt", "poses_tum.txt", "report.json"}) {
    EXPECT_TRUE(fs::exists(out() / name)) << name;
  }
  // The picture has its second row: the zoom where the drift's doubled walls got thin.
  const std::string png = test::readText(out() / "before_after.png");
  ASSERT_GT(png.size(), 24u);
  const auto height =
      static_cast<unsigned>(static_cast<unsigned char>(png[22])) << 8 | static_cast<unsigned char>(png[23]);
  EXPECT_EQ(height, 1100u + 770u);
  const double kitti = ateRmse(data() / "gt.txt", out() / "poses_kitti.txt", dir.path());
  EXPECT_NEAR(kitti, after, 1e-6);
  const nlohmann::json report = readJson(out() / "report.json");
  EXPECT_EQ(report.at("frames"), 120);
  EXPECT_GE(report.at("layers").get<int>(), 2);
  EXPECT_FALSE(report.at("layer_reports").empty());
  for (const auto& layer : report.at("layer_reports")) {
    EXPECT_GT(layer.at("planes").get<int>(), 0);
    EXPECT_LE(layer.at("plane_rms_after_m").get<double>(),
              layer.at("plane_rms_before_m").get<double>() + 1e-9);
  }
  const auto& first = report.at("iterations").at(0);
  EXPECT_LT(first.at("pose_graph_cost_after").get<double>(),
            first.at("pose_graph_cost_before").get<double>());
  EXPECT_GT(report.at("peak_memory_mib").get<double>(), 0.0);
  EXPECT_EQ(report.at("settings").at("window"), 0);  // automatic: dense scans keep the paper's 10
  EXPECT_TRUE(report.at("windows").at("automatic").get<bool>());
  EXPECT_EQ(report.at("windows").at("window"), 10);
  EXPECT_FALSE(report.at("final_voxel").at("coarsened").get<bool>());  // dense scans: 1 m planes
  EXPECT_EQ(report.at("final_voxel").at("chosen_m"), 1.0);

  // The simulator's gt.txt measures every window: one row per layer, and
  // on this drift the layers' windows and the final poses are closer to
  // the truth than the input (what the run is for).
  const auto& errors = report.at("window_errors");
  ASSERT_EQ(errors.size(), report.at("layer_reports").size());
  for (std::size_t i = 0; i < errors.size(); ++i) {
    const auto& row = errors.at(i);
    EXPECT_EQ(row.at("layer"), report.at("layer_reports").at(i).at("layer"));
    EXPECT_GT(row.at("pairs").get<int>(), 0);
    const double input = row.at("input").at("translation_rms_m").get<double>();
    EXPECT_LT(row.at("final").at("translation_rms_m").get<double>(), input) << "layer " << row.at("layer");
    EXPECT_LT(row.at("window").at("translation_rms_m").get<double>(), input) << "layer " << row.at("layer");
  }

  // Stage times: each measured, and together within the total (they are
  // sequential phases of one run; what is left is setup and bookkeeping).
  const auto& seconds = report.at("seconds");
  double stages = 0.0;
  for (const char* stage : {"read", "downsample", "voxelize", "solve", "keyframes", "pose_graph"}) {
    EXPECT_GT(seconds.at(stage).get<double>(), 0.0) << stage;
    stages += seconds.at(stage).get<double>();
  }
  EXPECT_LE(stages, seconds.at("total").get<double>());
  EXPECT_GT(stages, 0.5 * seconds.at("total").get<double>());
}

// Sparse scans (a VLP-16 thinned to 0.5 m) among trees and bushes: with
// planes of 1 m voxels, pooled from many scans' few points on curved
// surfaces, the layer-1 windows turned their frames further from the truth
// than the odometry had them, and the hierarchy was discarded. Planes of
// coarser voxels, chosen from the scans' density, make the windows better
// than their input and the hierarchy is kept. Shown on the paper's ten-scan
// windows (the automatic ones hold 34 of these scans and want fewer points
// of each: final_voxel.hpp).
TEST_F(OptimizeSimulated, SparseScansInTheOpenGetWindowsBetterThanTheirInput) {
  run(hba() + " -q simulate --frames 300 --sensor vlp16 --downsample 0.5 --scene open --noise 0.03 " +
      "--drift-translation 0.002 --drift-rotation 0.002 --jitter-rotation 0.02 --jitter-translation 0.005 " +
      "--seed 1 -o " + data().string());
  const std::string hierarchy_alone =
      " --window 10 --no-refine --no-render --no-report-page --no-convention-check -o " + out().string() +
      " --force";
  auto layerOne = [&](const nlohmann::json& report) { return report.at("window_errors").at(0); };
  auto rotation = [](const nlohmann::json& row, const char* poses) {
    return row.at(poses).at("rotation_rms_deg").get<double>();
  };

  run(hba() + " -q optimize " + data().string() + hierarchy_alone);
  const nlohmann::json report = readJson(out() / "report.json");
  EXPECT_TRUE(report.at("final_voxel").at("coarsened").get<bool>());
  EXPECT_GT(report.at("final_voxel").at("chosen_m").get<double>(), 1.0);
  const nlohmann::json row = layerOne(report);
  EXPECT_LT(rotation(row, "window"), rotation(row, "input"));
  EXPECT_LT(row.at("window").at("translation_rms_m").get<double>(),
            row.at("input").at("translation_rms_m").get<double>());
  EXPECT_FALSE(report.at("consistency").at("hierarchy_rejected").get<bool>());
  EXPECT_LT(ateRmse(data() / "gt.txt", out() / "pose.json", dir.path()),
            ateRmse(data() / "gt.txt", data() / "pose.json", dir.path()));

  // The failure it mends: the setting's 1 m planes.
  run(hba() + " -q optimize " + data().string() + hierarchy_alone + " --no-adapt-final-voxel");
  const nlohmann::json fixed = layerOne(readJson(out() / "report.json"));
  EXPECT_GT(rotation(fixed, "window"), 2.0 * rotation(fixed, "input"));
}

TEST_F(OptimizeSimulated, LoopClosedInputIsNotMadeWorse) {
  run(hba() + " -q simulate --frames 100 --seed 6 --loop-closed -o " + data().string());
  run(hba() + " -q optimize " + data().string() + " -o " + out().string());
  const double before = ateRmse(data() / "gt.txt", data() / "pose.json", dir.path());
  const double after = ateRmse(data() / "gt.txt", out() / "pose.json", dir.path());
  EXPECT_LE(after, before) << "before " << before << " m, after " << after << " m";
}

// A solid-state sensor (narrow field of view) with jittery odometry, in a
// building and in an open, vegetated scene: the scenes where short windows
// slide frames along directions their planes barely hold. The result must
// be far closer to the truth than the input and crisper; the open scene
// once ended 2.5 times further from the truth than its input.
TEST_F(OptimizeSimulated, NarrowFieldOfViewIndoorsAndInTheOpen) {
  for (const char* scene : {"indoor", "open"}) {
    const fs::path data = dir / scene;
    const fs::path out = dir / (std::string(scene) + "_out");
    run(hba() + " -q simulate --frames 200 --seed 12 --sensor livox --scene " + scene +
        " --jitter-translation 0.03 --jitter-rotation 0.2 -o " + data.string());
    run(hba() + " -q optimize " + data.string() + " -o " + out.string() + " --no-render");
    const double before = ateRmse(data / "gt.txt", data / "pose.json", dir.path());
    const double after = ateRmse(data / "gt.txt", out / "pose.json", dir.path());
    EXPECT_LT(after, before / 5.0) << scene << ": before " << before << " m, after " << after;
    const nlohmann::json report = readJson(out / "report.json");
    const auto& c = report.at("consistency");
    EXPECT_LT(c.at("final_rms_m").get<double>(), 0.6 * c.at("input_rms_m").get<double>()) << scene;
  }
}

// An odometry glitch: every pose from frame 60 on jumps 60 cm sideways.
// The slide checks must let through this correction, which every plane
// shared by the two halves demands, while they stop frames sliding where
// planes do not hold them: the jump is removed, not kept.
TEST_F(OptimizeSimulated, OdometryJumpOf60CentimetresIsCorrected) {
  run(hba() + " -q simulate --frames 120 --seed 5 --sensor hdl32 --drift-translation 0.01 -o " +
      data().string());
  std::istringstream lines(test::readText(data() / "pose.json"));
  std::ostringstream jumped;
  std::string line;
  for (int frame = 0; std::getline(lines, line); ++frame) {
    std::istringstream values(line);
    double v[7];
    for (double& x : v) values >> x;
    if (frame >= 60) v[1] += 0.6;
    jumped.precision(17);
    for (int k = 0; k < 7; ++k) jumped << v[k] << (k < 6 ? " " : "\n");
  }
  const fs::path poses = dir / "jumped.json";
  test::writeText(poses, jumped.str());
  run(hba() + " -q optimize " + data().string() + " --poses " + poses.string() + " --format hba -o " +
      out().string() + " --no-render");
  const double before = ateRmse(data() / "gt.txt", poses, dir.path());
  const double after = ateRmse(data() / "gt.txt", out() / "pose.json", dir.path());
  EXPECT_GT(before, 0.1);
  EXPECT_LT(after, 0.01) << "before " << before << " m, after " << after << " m";
}

TEST_F(OptimizeSimulated, DirectAssignAndSingleBaModesRun) {
  run(hba() + " -q simulate --frames 60 --seed 7 --drift-translation 0.03 -o " + data().string());
  const double before = ateRmse(data() / "gt.txt", data() / "pose.json", dir.path());
  for (const std::string mode : {"--top-down direct-assign", "--layers 1 --iterations 1"}) {
    SCOPED_TRACE(mode);
    run(hba() + " -q optimize " + data().string() + " -o " + out().string() + " --force " + mode);
    EXPECT_LT(ateRmse(data() / "gt.txt", out() / "pose.json", dir.path()), before);
  }
}

// --print-plan says what the run would do and stops: no -o, nothing written,
// and the run then does what it said.
TEST_F(OptimizeSimulated, PrintsItsPlanAndThenRunsIt) {
  run(hba() + " -q simulate --frames 40 --seed 2 -o " + data().string());
  const auto before = std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator());
  const test::CommandResult printed =
      test::runCommand(hba() + " -q -j 2 optimize " + data().string() + " --window 8 --print-plan");
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  const nlohmann::json plan = nlohmann::json::parse(printed.output);
  EXPECT_EQ(plan.at("frames"), 40);
  EXPECT_EQ(plan.at("threads"), 2);
  EXPECT_EQ(plan.at("windows").at("window"), 8);
  EXPECT_EQ(plan.at("windows").at("stride"), 4);
  EXPECT_GT(plan.at("memory_estimate").at("peak_mib").get<double>(), 0.0);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), before);

  run(hba() + " -q -j 2 optimize " + data().string() + " --window 8 --no-render -o " + out().string());
  const nlohmann::json report = test::readJson(out() / "report.json");
  EXPECT_EQ(report.at("windows"), plan.at("windows"));
  EXPECT_EQ(report.at("final_voxel"), plan.at("final_voxel"));
  EXPECT_EQ(report.at("layers"), plan.at("layers"));
  EXPECT_EQ(report.at("threads"), plan.at("threads"));
}

TEST_F(OptimizeSimulated, RefusesToWriteIntoTheInput) {
  run(hba() + " -q simulate --frames 12 --seed 8 -o " + data().string());
  const test::CommandResult result =
      test::runCommand(hba() + " optimize " + data().string() + " -o " + (data() / "out").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("inside the input folder"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(data() / "out"));
}

TEST_F(OptimizeSimulated, SettingsFileAndFlagsCombine) {
  run(hba() + " -q simulate --frames 30 --seed 9 -o " + data().string());
  test::writeText(dir / "settings.yaml", "window: 6\nstride: 3\nlocal:\n  eigen_ratio: 0.04\n");
  run(hba() + " -q optimize " + data().string() + " -o " + out().string() + " --config " +
      (dir / "settings.yaml").string() + " --stride 2");
  const nlohmann::json settings = readJson(out() / "report.json").at("settings");
  EXPECT_EQ(settings.at("window"), 6);  // from the file
  EXPECT_EQ(settings.at("stride"), 2);  // the flag wins
  EXPECT_DOUBLE_EQ(settings.at("local").at("eigen_ratio").get<double>(), 0.04);

  test::writeText(dir / "bad.yaml", "windw: 6\n");
  const test::CommandResult bad =
      test::runCommand(hba() + " optimize " + data().string() + " -o " + out().string() + " --config " +
                       (dir / "bad.yaml").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("unknown setting 'windw'"), std::string::npos) << bad.output;
}

// -j 1 reaches every parallel part, the pose graph's Ceres solve included
// (report.json says what it ran on), and two runs give the same bytes.
TEST_F(OptimizeSimulated, OneThreadIsByteIdenticalRunToRun) {
  run(hba() + " -q simulate --frames 40 --seed 4 -o " + data().string());
  const std::string command = hba() + " -q -j 1 optimize " + data().string() + " --no-render --force -o ";
  run(command + (dir / "a").string());
  run(command + (dir / "b").string());
  EXPECT_EQ(readJson(dir / "a" / "report.json").at("threads"), 1);
  EXPECT_FALSE(readJson(dir / "a" / "report.json").at("iterations").empty());
  for (const char* file : {"pose.json", "poses_kitti.txt", "poses_tum.txt"}) {
    EXPECT_EQ(test::readText(dir / "a" / file), test::readText(dir / "b" / file)) << file;
  }
}

// A shorthand flag sets every setting it stands for; a specific flag beside
// it wins, whatever their order on the line.
TEST_F(OptimizeSimulated, ShorthandFlagsYieldToSpecificOnes) {
  run(hba() + " -q simulate --frames 30 --seed 9 -o " + data().string());
  run(hba() + " -q optimize " + data().string() + " -o " + out().string() +
      " --no-render --voxel-local 2 --voxel 3 --top-down direct-assign");
  const nlohmann::json settings = readJson(out() / "report.json").at("settings");
  EXPECT_EQ(settings.at("local").at("voxel_size"), 2.0);
  EXPECT_EQ(settings.at("global").at("voxel_size"), 3.0);
  EXPECT_EQ(settings.at("voxel_scans"), 3.0);
  EXPECT_EQ(settings.at("top_down"), "direct_assign");
  EXPECT_EQ(settings.at("refine_groups"), true);  // every setting is in the report
}

// A renamed flag still reads under its earlier name.
TEST_F(OptimizeSimulated, EarlierFlagNamesStillRead) {
  const test::CommandResult printed =
      test::runCommand(hba() + " optimize --print-config --scan-voxel 0.15 --downsample-keyframes 0.3");
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  EXPECT_NE(printed.output.find("downsample_scans: 0.15"), std::string::npos) << printed.output;
  EXPECT_NE(printed.output.find("downsample_keyframes: 0.3"), std::string::npos) << printed.output;
}

// --iterations is a maximum: 50 asked, the rounds stop when the poses
// settle or their moves stop shrinking, and report.json says which.
TEST_F(OptimizeSimulated, OuterRoundsStopWhenThePosesSettle) {
  run(hba() + " -q simulate --frames 60 --seed 3 -o " + data().string());
  const auto rounds = [&](const std::string& flags, const std::string& name) {
    run(hba() + " -q optimize " + data().string() + " -o " + (dir / name).string() + " --no-render " + flags);
    return readJson(dir / name / "report.json");
  };
  const nlohmann::json asked = rounds("--iterations 50", "fifty");
  const nlohmann::json& stopped = asked.at("outer_iterations");
  EXPECT_LE(stopped.at("run").get<int>(), 5) << stopped;
  EXPECT_EQ(asked.at("iterations").size(), stopped.at("run").get<std::size_t>());
  EXPECT_NE(stopped.at("stopped"), "iteration limit") << stopped;
  const std::string reason = stopped.at("reason");
  EXPECT_TRUE(reason.rfind("settled after ", 0) == 0 || reason.rfind("stopped after ", 0) == 0) << reason;

  // Looser tolerances: settled after the second round, within them.
  const nlohmann::json loose =
      rounds("--iterations 50 --settle-rotation 0.05 --settle-translation 0.02", "loose");
  EXPECT_EQ(loose.at("outer_iterations").at("stopped"), "poses settled") << loose.at("outer_iterations");
  EXPECT_EQ(loose.at("outer_iterations").at("run"), 2);
  EXPECT_NE(loose.at("outer_iterations").at("reason").get<std::string>().find("(within 0.02 m, 0.05 deg)"),
            std::string::npos);
  EXPECT_EQ(loose.at("settings").at("settle_rotation"), 0.05);

  // The default: one round, said as such.
  const nlohmann::json once = rounds("", "once");
  EXPECT_EQ(once.at("outer_iterations").at("run"), 1);
  EXPECT_EQ(once.at("outer_iterations").at("stopped"), "iteration limit");
  EXPECT_EQ(once.at("outer_iterations").at("reason").get<std::string>().rfind("reached --iterations 1: ", 0),
            0u);
}

}  // namespace
}  // namespace hba

namespace hba {
namespace {

// The number that follows `marker` in the output of `command` (which must succeed).
double numberAfter(const std::string& command, const std::string& marker) {
  const test::CommandResult result = test::runCommand(command);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const auto at = result.output.rfind(marker);
  if (at == std::string::npos) {
    ADD_FAILURE() << marker << " not in: " << result.output;
    return 1e9;
  }
  return std::stod(result.output.substr(at + marker.size()));
}

// "MME -2.972112 (...)" -> -2.972112
double mmeOf(const std::string& dataset, const std::string& poses) {
  return numberAfter(hba() + " -q mme " + dataset + (poses.empty() ? "" : " --poses " + poses), "MME ");
}

// The real Livox sequence: the optimized map must be crisper (lower mean map
// entropy) than the odometry's, never less consistent.
TEST(OptimizeReal, Hku1MapGetsCrisper) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  run(hba() + " -q optimize " + data.string() + " -o " + (dir / "out").string() + " --no-render");
  const double before = mmeOf(data.string(), "");
  const double after = mmeOf(data.string(), (dir / "out" / "poses_kitti.txt").string());
  EXPECT_NEAR(before, -2.972, 0.005);
  EXPECT_LT(after, before - 0.01) << "before " << before << ", after " << after;
  // One global plane BA (--layers 1) reaches -3.030 here (BENCHMARKS.md):
  // the default keeps at least 90 % of that gain.
  const double global = -3.030;
  EXPECT_LT(after, before + 0.9 * (global - before)) << "after " << after;
}

// Optimized again from its own output, a converged map comes back
// unchanged, and the run says why (`data` optimized into `dir`/out first).
// Before, the refinement moved such a map along directions its planes
// barely hold (hku1 4.1 mm RMS, nclt 41 mm) and on nclt the closure graph
// alone 31 mm.
void expectAFixedPoint(const fs::path& data, const test::TempDir& dir) {
  const fs::path first = dir / "out" / "poses_kitti.txt";
  const fs::path again = dir / "again";
  const test::CommandResult r =
      test::runCommand(hba() + " optimize " + data.string() + " --poses " + first.string() +
                       " --no-render -o " + again.string() + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("the input is converged: its poses are returned unchanged"), std::string::npos)
      << r.output;
  // The same poses (to the rounding of reading a rotation matrix back).
  std::istringstream a(test::readText(again / "poses_kitti.txt")), b(test::readText(first));
  double x = 0.0, y = 0.0, largest = 0.0;
  std::size_t numbers = 0;
  while (a >> x && b >> y) {
    largest = std::max(largest, std::abs(x - y));
    ++numbers;
  }
  EXPECT_GT(numbers, 0u);
  EXPECT_LT(largest, 1e-12);
  const nlohmann::json report = readJson(again / "report.json");
  EXPECT_TRUE(report.at("refinement").at("converged_at_start").get<bool>());
  // Below the refinement's gate (ba::RefinementSettings::significant_gain;
  // nclt's automatic windows leave 1.35).
  EXPECT_LE(report.at("refinement").at("gain_over_noise").get<double>(),
            ba::RefinementSettings{}.significant_gain);
  EXPECT_EQ(report.at("largest_update").at("translation_m").get<double>(), 0.0);
  // Nothing the user must act on: the hierarchy's poses were not needed.
  for (const auto& warning : report.at("warnings"))
    EXPECT_EQ(warning.get<std::string>().find("less consistent"), std::string::npos) << warning;
  EXPECT_EQ(r.output.find("[warning] frames 0-"), std::string::npos) << r.output;
  // Nor do the windows, which a coarse round may carry off such a map
  // (nclt's window 962-1014 slid frames, before it was solved again).
  EXPECT_EQ(r.output.find("made the map blurrier"), std::string::npos) << r.output;
}

// On a simulation the hierarchy run again is not less consistent, only no
// more than fitting the noise would make it: the input is refined instead
// and comes back unchanged (before: moved 0.08 mm RMS, 1000 Livox frames 1.7 mm).
TEST_F(OptimizeSimulated, ItsOwnOutputOptimizedAgainIsAFixedPoint) {
  run(hba() + " -q simulate --frames 120 --seed 5 --drift-translation 0.03 --drift-rotation 0.05 -o " +
      data().string());
  run(hba() + " -q optimize " + data().string() + " -o " + (dir / "out").string() + " --no-render");
  expectAFixedPoint(data(), dir);
  const nlohmann::json again = readJson(dir / "again" / "report.json");
  EXPECT_TRUE(again.at("consistency").at("hierarchy_insignificant").get<bool>());
  EXPECT_FALSE(
      readJson(dir / "out" / "report.json").at("consistency").at("hierarchy_insignificant").get<bool>());
}

// The hierarchy alone (--no-refine) started from the default run's output:
// every window finds nothing beyond fitting noise to correct and keeps its
// start (the settle check), and so does the top layer above them, so the
// pyramid returns the map it was given (to rounding). Before, its windows
// each went to an optimum of their own and the hierarchy's map was less
// consistent than its input; then the top alone still moved it (hku1 3.9 mm
// RMS). From the drifting input, the same windows all have work to do. One
// global BA of the scans (--layers 1) never settles.
TEST_F(OptimizeSimulated, TheHierarchyAloneLeavesItsOwnOutputAlone) {
  run(hba() + " -q simulate --frames 120 --seed 5 --drift-translation 0.03 --drift-rotation 0.05 -o " +
      data().string());
  const fs::path first = dir / "out";
  run(hba() + " -q optimize " + data().string() + " -o " + first.string() + " --no-render");
  // Held by name: a range-for over a temporary's member would read freed memory.
  const nlohmann::json first_report = readJson(first / "report.json");
  for (const auto& layer : first_report.at("layer_reports")) {
    if (layer.at("layer").get<int>() == 1) {
      EXPECT_EQ(layer.at("windows_settled").get<int>(), 0) << layer;
    }
  }

  const fs::path again = dir / "again";
  const test::CommandResult r = test::runCommand(hba() + " optimize " + data().string() + " --poses " +
                                                 (first / "poses_kitti.txt").string() +
                                                 " --no-refine --no-render -o " + again.string() + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json report = readJson(again / "report.json");
  std::size_t settled = 0;
  for (const auto& layer : report.at("layer_reports")) {
    const auto windows = layer.at("windows").get<std::size_t>();
    EXPECT_EQ(
        layer.at("windows_settled").get<std::size_t>() + layer.at("windows_untrusted").get<std::size_t>(),
        windows)
        << layer;
    settled += layer.at("windows_settled").get<std::size_t>();
  }
  EXPECT_GT(settled, 0u);
  EXPECT_NE(r.output.find("windows settled"), std::string::npos) << r.output;
  // What the top then moves is no more than fitting noise: the input is returned.
  const nlohmann::json& consistency = report.at("consistency");
  EXPECT_FALSE(consistency.at("hierarchy_rejected").get<bool>());
  EXPECT_LE(consistency.at("hierarchy_rms_m").get<double>(),
            consistency.at("input_rms_m").get<double>() * 1.001);
  EXPECT_EQ(report.at("largest_update").at("translation_m").get<double>(), 0.0);
  for (const auto& warning : report.at("warnings"))
    EXPECT_EQ(warning.get<std::string>().find("less consistent"), std::string::npos) << warning;
  // The hierarchy's own poses, not only the run's: the top-down step moved
  // nothing but rounding (chaining relative poses: 4e-14 m).
  const nlohmann::json& round = report.at("iterations").at(0);
  EXPECT_LT(round.at("max_translation_update_m").get<double>(), 1e-9) << round;
  EXPECT_LT(round.at("max_rotation_update_deg").get<double>(), 1e-9) << round;

  const fs::path global = dir / "global";
  run(hba() + " -q optimize " + data().string() + " --poses " + (first / "poses_kitti.txt").string() +
      " --no-refine --no-render --layers 1 -o " + global.string());
  const nlohmann::json global_report = readJson(global / "report.json");
  ASSERT_EQ(global_report.at("layer_reports").size(), 1u);
  EXPECT_EQ(global_report.at("layer_reports").at(0).at("windows_settled").get<int>(), 0);
}

// A converged map of HDL-32 scans: from it, a third of the layer-1 windows
// ended blurrier on their input's 1 m planes than they started, once the
// 2 m round had carried them off and the 1 m round, on planes found where
// they went, had not brought them back; they kept their input poses, and the
// run warned that they "made the map blurrier" (7 of 23 windows here; 72 of
// 199 on 1000 frames). Solved again on those planes from their input, they
// gain no more than fitting noise and settle: nothing to warn of. They
// settle on a Gauss-Newton step's prediction, without the solve; with a
// settle check of 2 instead of 8, six of them need the solve.
TEST_F(OptimizeSimulated, AConvergedMapsWindowsDoNotCallItBlurrier) {
  run(hba() + " -q simulate --frames 120 --sensor hdl32 --seed 2 -o " + data().string());
  const fs::path first = dir / "out";
  run(hba() + " -q optimize " + data().string() + " -o " + first.string() + " --no-render --no-report-page");
  test::writeText(dir / "settle2.yaml", "local:\n  significant_gain: 2\n");
  for (const std::string& extra :
       std::vector<std::string>{"", " --config " + (dir / "settle2.yaml").string()}) {
    const fs::path again = dir / "again";
    const test::CommandResult r = test::runCommand(
        hba() + " optimize " + data().string() + " --poses " + (first / "poses_kitti.txt").string() +
        " --no-refine --no-render --no-report-page --force -o " + again.string() + extra + " 2>&1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("made the map blurrier"), std::string::npos) << extra << r.output;
    const nlohmann::json report = readJson(again / "report.json");
    const nlohmann::json& layer1 = report.at("layer_reports").at(0);
    ASSERT_EQ(layer1.at("layer").get<int>(), 1);
    EXPECT_GT(layer1.at("windows_solved_again").get<std::size_t>(), 0u) << extra << layer1;
    EXPECT_EQ(layer1.at("windows_untrusted").get<std::size_t>(), 0u) << extra << layer1;
    if (extra.empty()) {
      EXPECT_GT(layer1.at("windows_settled").get<std::size_t>(), layer1.at("windows").get<std::size_t>() / 2)
          << layer1;
      EXPECT_EQ(report.at("largest_update").at("translation_m").get<double>(), 0.0);
    }
  }
}

TEST(OptimizeReal, Hku1OutputOptimizedAgainIsAFixedPoint) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  run(hba() + " -q optimize " + data.string() + " -o " + (dir / "out").string() + " --no-render");
  expectAFixedPoint(data, dir);
}

// The hierarchy alone (--no-refine) on the real Livox sequence: a window as
// one factor of its whole shape (the default) keeps how its frames move
// together, which pairs of frames drop, and gives the crisper map
// (measured: input -2.972, adjacent pairs -2.989, whole windows -3.001).
TEST(OptimizeReal, Hku1HierarchyAloneIsCrisperWithWholeWindowFactors) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  const std::string common = hba() + " -q optimize " + data.string() + " --no-render --no-refine -o ";
  run(common + (dir / "joint").string());
  run(common + (dir / "adjacent").string() + " --pairs adjacent");
  const double before = mmeOf(data.string(), "");
  const double joint = mmeOf(data.string(), (dir / "joint" / "poses_kitti.txt").string());
  const double adjacent = mmeOf(data.string(), (dir / "adjacent" / "poses_kitti.txt").string());
  EXPECT_LT(joint, before - 0.02) << "before " << before << ", whole windows " << joint;
  EXPECT_LT(joint, adjacent - 0.006) << "whole windows " << joint << ", adjacent pairs " << adjacent;
}

// "ATE trans m     0.224242 ..." -> 0.224242 (the RMSE column)
double ateRmse(const fs::path& gt, const fs::path& est) {
  return numberAfter(hba() + " -q eval --gt " + gt.string() + " --est " + est.string(), "ATE trans m");
}

// The real HDL-32E sequence on which the pyramid alone warped the map by
// 22 m: the result must be crisper than the odometry, keep 90 % of one
// global BA's gain (-3.301, BENCHMARKS.md) and stay within 0.5 m of the
// loop-closed reference (measured: 0.36 m; its last scans end 1 m from the
// reference, towards RTK: docs/pyramid.md, "Automatic windows").
TEST(OptimizeReal, NcltMapGetsCrisperWithoutWarping) {
  const fs::path data = test::sharedDataDir() / "nclt";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  test::TempDir dir;
  run(hba() + " -q optimize " + data.string() + " -o " + (dir / "out").string() + " --no-render");
  const fs::path poses = dir / "out" / "poses_kitti.txt";
  const double before = mmeOf(data.string(), "");
  const double after = mmeOf(data.string(), poses.string());
  EXPECT_NEAR(before, -3.252, 0.005);
  const double global = -3.301;
  EXPECT_LT(after, before + 0.9 * (global - before)) << "after " << after;
  EXPECT_LT(ateRmse(data / "optimized_poses.txt", poses), 0.5);
  // No pose moves many metres: the odometry is locally good (measured: 1.38 m, the last scans).
  const nlohmann::json report = readJson(dir / "out" / "report.json");
  EXPECT_LT(report.at("largest_update").at("translation_m").get<double>(), 2.0);
  EXPECT_TRUE(report.at("consistency").at("hierarchy_rejected").is_boolean());
  EXPECT_LT(report.at("consistency").at("final_rms_m").get<double>(),
            report.at("consistency").at("input_rms_m").get<double>());
  // Its 16 revisit loops hold at its output: nothing for the closure graph.
  expectAFixedPoint(data, dir);
  EXPECT_TRUE(readJson(dir / "again" / "report.json").at("closure").at("held_at_input").get<bool>());
}

}  // namespace
}  // namespace hba
