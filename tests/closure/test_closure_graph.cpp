#include <gtest/gtest.h>

#include <random>

#include "closure_paths.hpp"
#include "hba/closure/closure_graph.hpp"

namespace hba::closure {
namespace {

// A loop factor from the truth: exact, with centimetre-level information.
graph::LoopClosureFactor trueLoop(const std::vector<Pose>& truth, std::size_t from, std::size_t to) {
  graph::LoopClosureFactor f;
  f.from = from;
  f.to = to;
  f.measurement = relative(truth[from], truth[to]);
  f.information = Mat6::Identity() * 1e4;
  return f;
}

class ClosureGraph : public ::testing::Test {
 protected:
  // 400 frames round a 60 m circle; the odometry opens it by metres.
  std::vector<Pose> truth = test::circle(400, 60.0);
  std::vector<Pose> odometry = test::drifted(truth, 0.04, 0.002, 3);
};

TEST_F(ClosureGraph, TrueLoopsCloseTheCircle) {
  ASSERT_GT(test::largestError(odometry, truth), 10.0);
  std::vector<graph::LoopClosureFactor> loops{trueLoop(truth, 0, 399), trueLoop(truth, 10, 390),
                                              trueLoop(truth, 5, 395)};
  const ClosureGraphResult r = solveClosureGraph(odometry, loops, {}, ClosureGraphSettings{});
  for (bool kept : r.loop_kept) EXPECT_TRUE(kept);
  // Each loop end now sits where the truth puts it relative to the other.
  EXPECT_LT((relative(r.poses[0], r.poses[399]).t - relative(truth[0], truth[399]).t).norm(), 0.01);
  // The heading bias is spread along the path: metres become decimetres.
  EXPECT_LT(test::largestError(r.poses, truth), 0.1 * test::largestError(odometry, truth));
}

TEST_F(ClosureGraph, AWrongLoopIsDroppedAndChangesNothing) {
  std::vector<graph::LoopClosureFactor> right{trueLoop(truth, 0, 399), trueLoop(truth, 10, 390),
                                              trueLoop(truth, 5, 395)};
  std::vector<graph::LoopClosureFactor> with_wrong = right;
  // A place recognizer's mistake: frames half a circle apart "coincide".
  graph::LoopClosureFactor wrong = trueLoop(truth, 100, 300);
  wrong.measurement = Pose();
  with_wrong.insert(with_wrong.begin() + 1, wrong);

  const ClosureGraphResult clean = solveClosureGraph(odometry, right, {}, ClosureGraphSettings{});
  const ClosureGraphResult r = solveClosureGraph(odometry, with_wrong, {}, ClosureGraphSettings{});
  ASSERT_EQ(r.loop_kept.size(), 4u);
  EXPECT_FALSE(r.loop_kept[1]);
  EXPECT_TRUE(r.loop_kept[0] && r.loop_kept[2] && r.loop_kept[3]);
  EXPECT_LT(test::largestError(r.poses, clean.poses), 1e-6);
}

TEST_F(ClosureGraph, PriorsSetTheFrameAndOutliersAreDropped) {
  // Priors every 10 frames with 0.5 m noise, in a frame shifted and turned
  // from the odometry's; three of them 20 m off.
  const Pose world(Mat3(Eigen::AngleAxisd(0.3, Vec3::UnitZ())), Vec3(500.0, -200.0, 30.0));
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<graph::PositionPriorFactor> priors;
  for (std::size_t k = 0; k < truth.size(); k += 10) {
    graph::PositionPriorFactor f;
    f.node = k;
    f.position = (world * truth[k]).t + Vec3(noise(rng), noise(rng), noise(rng));
    f.information = Mat3::Identity() / 0.25;
    priors.push_back(f);
  }
  for (std::size_t k : {7u, 19u, 33u}) priors[k].position += Vec3(20.0, 0.0, 0.0);

  const ClosureGraphResult r = solveClosureGraph(odometry, {}, priors, ClosureGraphSettings{});
  for (std::size_t k = 0; k < priors.size(); ++k) {
    EXPECT_EQ(r.prior_kept[k], k != 7 && k != 19 && k != 33) << "prior " << k;
  }
  std::vector<Pose> truth_in_world;
  for (const Pose& p : truth) truth_in_world.push_back(world * p);
  // Metres of drift in another frame become errors below the priors' noise.
  double squares = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k)
    squares += (r.poses[k].t - truth_in_world[k].t).squaredNorm();
  EXPECT_LT(std::sqrt(squares / static_cast<double>(truth.size())), 0.5);
  EXPECT_LT(test::largestError(r.poses, truth_in_world), 1.0);
}

TEST_F(ClosureGraph, ACircleItClosedIsLeftAlone) {
  const std::vector<graph::LoopClosureFactor> loops{trueLoop(truth, 0, 399), trueLoop(truth, 10, 390)};
  const ClosureGraphResult first = solveClosureGraph(odometry, loops, {}, ClosureGraphSettings{});
  ASSERT_FALSE(first.held_at_input);
  ASSERT_GT(first.rounds, 0);
  // Its own output given again: every loop holds there, nothing is solved
  // and nothing moves (solved again, the poses would creep by the loops'
  // and steps' disagreement).
  const ClosureGraphResult again = solveClosureGraph(first.poses, loops, {}, ClosureGraphSettings{});
  EXPECT_TRUE(again.held_at_input);
  EXPECT_EQ(again.rounds, 0);
  EXPECT_EQ(test::largestError(again.poses, first.poses), 0.0);
  // A loop 10 cm off at the input (beyond the 5 cm tolerance) is closed.
  std::vector<Pose> opened = first.poses;
  for (std::size_t k = 200; k < opened.size(); ++k) opened[k].t += Vec3(0.0, 0.0, 0.1 * (k - 200) / 199.0);
  const ClosureGraphResult reopened = solveClosureGraph(opened, loops, {}, ClosureGraphSettings{});
  EXPECT_FALSE(reopened.held_at_input);
  EXPECT_LT((relative(reopened.poses[0], reopened.poses[399]).t - relative(truth[0], truth[399]).t).norm(),
            0.01);
}

TEST_F(ClosureGraph, NothingToCloseReturnsTheInput) {
  const ClosureGraphResult r = solveClosureGraph(odometry, {}, {}, ClosureGraphSettings{});
  EXPECT_EQ(r.rounds, 0);
  EXPECT_EQ(test::largestError(r.poses, odometry), 0.0);
}

}  // namespace
}  // namespace hba::closure

namespace hba::closure {
namespace {

TEST(ClosureGraphSessions, ASessionIsMovedOnlyByWhatTiesItToTheOthers) {
  // Session A: 200 frames round a circle; session B: the same circle again,
  // its input placed 20 m and 10 degrees off. One true loop between them.
  const std::vector<Pose> lap = test::circle(200, 30.0);
  std::vector<Pose> truth = lap;
  truth.insert(truth.end(), lap.begin(), lap.end());
  const Pose misplaced(Mat3(Eigen::AngleAxisd(0.17, Vec3::UnitZ())), Vec3(20.0, 0.0, 0.0));
  std::vector<Pose> input = lap;
  for (const Pose& p : lap) input.push_back(misplaced * p);

  const ClosureGraphResult alone = solveClosureGraph(input, {}, {}, ClosureGraphSettings{}, {200});
  EXPECT_EQ(alone.rounds, 0);  // nothing ties them: nothing to solve
  graph::LoopClosureFactor loop;
  loop.from = 50;
  loop.to = 250;
  loop.measurement = relative(truth[50], truth[250]);
  loop.information = Mat6::Identity() * 1e4;
  const ClosureGraphResult joined = solveClosureGraph(input, {loop}, {}, ClosureGraphSettings{}, {200});
  // A keeps its poses (it holds the gauge); B comes onto it as a whole:
  // no step of the input links frame 199 to frame 200.
  EXPECT_LT(test::largestError(std::vector<Pose>(joined.poses.begin(), joined.poses.begin() + 200), lap),
            1e-6);
  EXPECT_LT(test::largestError(joined.poses, truth), 1e-3);
}

}  // namespace
}  // namespace hba::closure
