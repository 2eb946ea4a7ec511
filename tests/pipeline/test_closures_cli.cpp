// `hba optimize` with closures end to end (docs/closure.md): revisits found
// and closed, loop pairs with wrong ones among them, position priors in
// another frame, two sessions in their own frames. Small simulated
// sequences with ground truth.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_runs.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/pose_file.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

using test::readJson;
std::string hba() { return test::hbaTool(); }
void run(const std::string& command) { test::runOk(command); }

// ATE translation RMSE (m) of `est` against `gt`, aligned as `align` says.
double ate(const fs::path& gt, const fs::path& est, const fs::path& scratch,
           const std::string& align = "se3") {
  return test::evalRmse("ate", gt, est, scratch, "--align " + align);
}

// RPE translation RMSE (m) over 10 frames.
double rpe(const fs::path& gt, const fs::path& est, const fs::path& scratch) {
  return test::evalRmse("rpe", gt, est, scratch, "--delta 10");
}

// True revisits of a simulated sequence: for frames from `from_frame` on,
// the earlier frame (at least `min_gap` frames back) nearest by the truth,
// when nearer than 2 m; every `every`-th one.
std::vector<std::pair<std::size_t, std::size_t>> trueRevisits(const Trajectory& gt, std::size_t min_gap,
                                                              std::size_t every) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t j = min_gap; j < gt.size(); ++j) {
    std::size_t best = gt.size();
    for (std::size_t i = 0; i + min_gap <= j; ++i) {
      const double d = (gt.poses[i].t - gt.poses[j].t).norm();
      if (d < 2.0 && (best == gt.size() || d < (gt.poses[best].t - gt.poses[j].t).norm())) best = i;
    }
    if (best < gt.size()) pairs.emplace_back(best, j);
  }
  std::vector<std::pair<std::size_t, std::size_t>> kept;
  for (std::size_t k = 0; k < pairs.size(); k += every) kept.push_back(pairs[k]);
  return kept;
}

class ClosuresSimulated : public testing::Test {
 protected:
  test::TempDir dir;
  fs::path data() const { return dir / "sequence"; }
};

// In an open scene the windows cannot see the odometry's drift: the drive
// returns metres from where it started, and the hierarchy alone does not
// close it. By default the return is found, verified and closed.
TEST_F(ClosuresSimulated, AnOpenLoopRevisitMetresOffIsFoundAndClosed) {
  run(hba() + " -q simulate --frames 800 --seed 3 --scene open -o " + data().string());
  run(hba() + " -q optimize " + data().string() + " --no-render --no-revisits -o " +
      (dir / "plain").string());
  run(hba() + " -q optimize " + data().string() + " --no-render -o " + (dir / "closed").string());

  const double input = ate(data() / "gt.txt", data() / "pose.json", dir.path());
  const double plain = ate(data() / "gt.txt", dir / "plain" / "pose.json", dir.path());
  const double closed = ate(data() / "gt.txt", dir / "closed" / "pose.json", dir.path());
  EXPECT_GT(input, 0.5);
  // The hierarchy alone keeps the map crisp but bends its open loop.
  EXPECT_GT(plain, 0.5);
  EXPECT_LT(closed, 0.005) << "input " << input << " m, hierarchy alone " << plain << " m";

  // With --no-revisits the report still says where the poses come back.
  const nlohmann::json without = readJson(dir / "plain" / "report.json").at("closure");
  EXPECT_GT(without.at("revisit_candidates").get<int>(), 0);
  EXPECT_FALSE(without.at("revisits_searched").get<bool>());
  const nlohmann::json with = readJson(dir / "closed" / "report.json").at("closure");
  EXPECT_TRUE(with.at("revisits_searched").get<bool>());
  EXPECT_GT(with.at("loops_used").get<int>(), 0);
  EXPECT_EQ(with.at("loops").size(), with.at("revisit_candidates").get<std::size_t>());
}

// A loop file with a fifth of its pairs wrong (places tens of metres apart):
// the wrong ones are rejected and counted, and the poses are those of the
// right pairs alone.
TEST_F(ClosuresSimulated, WrongLoopPairsAreRejectedAndCounted) {
  run(hba() +
      " -q simulate --frames 400 --seed 3 --scene open --drift-translation 0.02 --drift-rotation 0.04 -o " +
      data().string());
  const Trajectory gt = io::readPoses(data() / "gt.txt");
  const auto right = trueRevisits(gt, 250, 15);
  ASSERT_GE(right.size(), 4u);
  std::vector<std::pair<std::size_t, std::size_t>> wrong;
  std::mt19937 rng(9);
  std::uniform_int_distribution<std::size_t> frame(0, gt.size() - 1);
  while (wrong.size() * 4 < right.size()) {
    const std::size_t i = frame(rng), j = frame(rng);
    if (i + 100 < j && (gt.poses[i].t - gt.poses[j].t).norm() > 40.0) wrong.emplace_back(i, j);
  }
  const auto write = [&](const fs::path& path, bool with_wrong) {
    std::ofstream out(path);
    for (const auto& [i, j] : right) out << i << ' ' << j << '\n';
    if (with_wrong) {
      for (const auto& [i, j] : wrong) out << i << ' ' << j << '\n';
    }
  };
  write(dir / "right.txt", false);
  write(dir / "mixed.txt", true);
  run(hba() + " -q optimize " + data().string() + " --no-render --loops " + (dir / "right.txt").string() +
      " -o " + (dir / "right").string());
  run(hba() + " -q optimize " + data().string() + " --no-render --loops " + (dir / "mixed.txt").string() +
      " -o " + (dir / "mixed").string());

  const nlohmann::json report = readJson(dir / "mixed" / "report.json").at("closure");
  EXPECT_EQ(report.at("loops_given").get<std::size_t>(), right.size() + wrong.size());
  std::size_t wrong_used = 0, right_used = 0;
  for (const auto& loop : report.at("loops")) {
    const std::pair<std::size_t, std::size_t> pair{loop.at("from").get<std::size_t>(),
                                                   loop.at("to").get<std::size_t>()};
    const bool is_wrong = std::find(wrong.begin(), wrong.end(), pair) != wrong.end();
    if (is_wrong) {
      EXPECT_FALSE(loop.at("reason").get<std::string>().empty());
      wrong_used += loop.at("used").get<bool>() ? 1 : 0;
    } else {
      right_used += loop.at("used").get<bool>() ? 1 : 0;
    }
  }
  EXPECT_EQ(wrong_used, 0u);
  EXPECT_GT(right_used, 0u);
  EXPECT_GE(report.at("rejected_by_planes").get<std::size_t>() +
                report.at("dropped_as_inconsistent").get<std::size_t>(),
            wrong.size());
  const double with_right = ate(data() / "gt.txt", dir / "right" / "pose.json", dir.path());
  const double with_mixed = ate(data() / "gt.txt", dir / "mixed" / "pose.json", dir.path());
  EXPECT_LT(with_right, 0.005);
  EXPECT_NEAR(with_mixed, with_right, 1e-6);
}

// Priors with 0.3 m noise in a frame far from the odometry's (UTM-sized,
// turned), three of them 25 m off: the map comes out in the priors' frame,
// the outliers are dropped, and it is as crisp as without priors.
TEST_F(ClosuresSimulated, PositionPriorsSetTheFrameAndOutliersAreDropped) {
  run(hba() + " -q simulate --frames 240 --seed 5 -o " + data().string());
  const Trajectory gt = io::readPoses(data() / "gt.txt");
  const Pose utm(Mat3(Eigen::AngleAxisd(0.6, Vec3::UnitZ())), Vec3(431200.0, 5410300.0, 250.0));
  Trajectory gt_utm = gt;
  for (Pose& p : gt_utm.poses) p = utm * p;
  io::writePoses(dir / "gt_utm.txt", gt_utm, io::PoseFormat::Tum);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.3);
  {
    std::ofstream out(dir / "gnss.txt");
    out.precision(12);
    for (std::size_t k = 0; k < gt.size(); k += 5) {
      Vec3 p = gt_utm.poses[k].t + Vec3(noise(rng), noise(rng), noise(rng));
      if (k == 50 || k == 120 || k == 200) p.x() += 25.0;
      out << gt.stamps[k] + 0.02 << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << " 0.3\n";
    }
  }
  run(hba() + " -q optimize " + data().string() + " --no-render -o " + (dir / "plain").string());
  run(hba() + " -q optimize " + data().string() + " --no-render --priors " + (dir / "gnss.txt").string() +
      " -o " + (dir / "priors").string());

  const nlohmann::json report = readJson(dir / "priors" / "report.json").at("closure");
  EXPECT_EQ(report.at("priors_given").get<int>(), 48);
  EXPECT_EQ(report.at("priors_dropped").get<int>(), 3);
  // One block: the refinement holds the 45 kept priors itself, nothing re-anchors after it.
  const nlohmann::json refinement = readJson(dir / "priors" / "report.json").at("refinement");
  EXPECT_EQ(refinement.at("position_priors").get<int>(), 45);
  EXPECT_EQ(report.at("anchoring_move_m").get<double>(), 0.0);
  // In the priors' frame, without any alignment: within their noise.
  EXPECT_LT(ate(dir / "gt_utm.txt", dir / "priors" / "poses_tum.txt", dir.path(), "none"), 0.2);
  // Locally the map is the BA's: the priors' noise bends it by millimetres
  // over the whole drive, and the steps between frames are as accurate.
  const double plain = ate(data() / "gt.txt", dir / "plain" / "pose.json", dir.path());
  const double with_priors = ate(dir / "gt_utm.txt", dir / "priors" / "poses_tum.txt", dir.path());
  EXPECT_LT(with_priors, 0.01) << "without priors " << plain;
  const double plain_step = rpe(data() / "gt.txt", dir / "plain" / "pose.json", dir.path());
  const double priors_step = rpe(dir / "gt_utm.txt", dir / "priors" / "poses_tum.txt", dir.path());
  EXPECT_LT(priors_step, 1.2 * plain_step + 1e-4) << "without priors " << plain_step;
}

// Two sessions of one block, each in its own frame (the second starts 50 m
// further along the path, half a lap round): registered, joined by their
// revisits, and both within millimetres of the truth in the first's frame.
TEST_F(ClosuresSimulated, TwoSessionsInTheirOwnFramesMeetInOneMap) {
  run(hba() + " -q simulate --sessions 2 --frames 300 --session-frames 200 --seed 4 -o " + data().string());
  run(hba() + " -q optimize " + (data() / "session-0").string() + " " + (data() / "session-1").string() +
      " --no-render -o " + (dir / "joint").string());
  const nlohmann::json report = readJson(dir / "joint" / "report.json");
  ASSERT_EQ(report.at("sessions").size(), 2u);
  EXPECT_GT(report.at("closure").at("loops_used").get<int>(), 0);
  for (int k = 0; k < 2; ++k) {
    const std::string name = "session-" + std::to_string(k);
    EXPECT_LT(ate(data() / name / "gt_world.txt", dir / "joint" / name / "poses_tum.txt", dir.path(), "none"),
              0.005)
        << name;
  }
  // Where the second session's frame ended up, against the truth.
  const Trajectory truth = io::readPoses(data() / "session-1" / "gt_world.txt");
  const Trajectory own = io::readPoses(data() / "session-1" / "gt.txt");
  const Pose true_frame = truth.poses.front() * own.poses.front().inverse();
  std::ifstream in(dir / "joint" / "session-1" / "session_frame.txt");
  std::string comment;
  std::getline(in, comment);
  double tx, ty, tz, qx, qy, qz, qw;
  in >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
  EXPECT_LT((Vec3(tx, ty, tz) - true_frame.t).norm(), 0.05);
}

// Two sessions, each in its own frame, with GNSS-like priors (0.1 m noise,
// every 5th frame of each, in a UTM-sized turned frame): both sessions come
// out in the priors' frame, each prior on the session it was stamped in.
TEST_F(ClosuresSimulated, PriorsPlaceEverySessionInTheirFrame) {
  run(hba() + " -q simulate --sessions 2 --frames 300 --session-frames 200 --seed 4 -o " + data().string());
  const Pose utm(Mat3(Eigen::AngleAxisd(-0.9, Vec3::UnitZ())), Vec3(512300.0, 4120900.0, 80.0));
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::ofstream gnss(dir / "gnss.txt");
  gnss.precision(12);
  for (int k = 0; k < 2; ++k) {
    const std::string name = "session-" + std::to_string(k);
    Trajectory truth = io::readPoses(data() / name / "gt_world.txt");
    for (Pose& pose : truth.poses) pose = utm * pose;
    io::writePoses(dir / (name + "_utm.txt"), truth, io::PoseFormat::Tum);
    for (std::size_t i = 0; i < truth.size(); i += 5) {
      const Vec3 p = truth.poses[i].t + Vec3(noise(rng), noise(rng), noise(rng));
      gnss << truth.stamps[i] << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << " 0.1\n";
    }
  }
  gnss.close();
  run(hba() + " -q optimize " + (data() / "session-0").string() + " " + (data() / "session-1").string() +
      " --no-render --priors " + (dir / "gnss.txt").string() + " -o " + (dir / "joint").string());
  EXPECT_EQ(readJson(dir / "joint" / "report.json").at("closure").at("priors_given").get<int>(), 80);
  for (int k = 0; k < 2; ++k) {
    const std::string name = "session-" + std::to_string(k);
    EXPECT_LT(ate(dir / (name + "_utm.txt"), dir / "joint" / name / "poses_tum.txt", dir.path(), "none"),
              0.05)
        << name;
  }
}

// Bad closure input fails at once, naming the file and the problem, and
// writes nothing.
TEST_F(ClosuresSimulated, BadClosureInputFailsBeforeAnyWork) {
  run(hba() + " -q simulate --frames 30 --seed 2 -o " + data().string());
  const auto fails = [&](const std::string& flags, const std::vector<std::string>& words) {
    const test::CommandResult r = test::runCommand(hba() + " optimize " + data().string() + " -o " +
                                                   (dir / "out").string() + " " + flags);
    EXPECT_NE(r.exit_code, 0) << flags;
    for (const std::string& w : words)
      EXPECT_NE(r.output.find(w), std::string::npos) << flags << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << flags;
  };
  test::writeText(dir / "loops.txt", "3 12\n4 30\n");
  fails("--loops " + (dir / "loops.txt").string(), {"loops.txt", "line 2", "beyond the sequence"});
  test::writeText(dir / "gnss.txt", "0.5 1 2 3 0\n");
  fails("--priors " + (dir / "gnss.txt").string(), {"gnss.txt", "line 1", "sigma must be positive"});
  test::writeText(dir / "late.txt", "900 1 2 3 0.5\n");
  fails("--priors " + (dir / "late.txt").string(), {"late.txt", "no prior falls within"});
  // A second session: a copy of the first (the same folder twice is refused
  // as such, MapCli.OneSessionGivenTwiceIsRefused).
  const fs::path copy = dir / "copy";
  fs::copy(data(), copy, fs::copy_options::recursive);
  fails(copy.string() + " --poses " + (data() / "pose.json").string(), {"several sessions"});
  test::writeText(dir / "align.txt", "1 2 3 0 0 0 1\n1 2 3 0 0 0 1\n");
  fails(copy.string() + " --align " + (dir / "align.txt").string(), {"align.txt", "2 transforms for 1"});
  // Two sessions recorded at the same time: a prior falls among the scans of both.
  test::writeText(dir / "within.txt", "1.0 1 2 3 0.5\n");
  fails(copy.string() + " --priors " + (dir / "within.txt").string(),
        {"within.txt", "line 1", "sessions 0 and 1", "overlap"});
}

}  // namespace
}  // namespace hba
