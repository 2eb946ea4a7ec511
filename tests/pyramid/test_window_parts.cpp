// The parts of a layer's pass, one window at a time: its BA, its summary,
// its keyframe.
#include <gtest/gtest.h>

#include "hand_made_plan.hpp"
#include "hba/settings/settings.hpp"
#include "keyframe.hpp"
#include "simulated_sequence.hpp"
#include "window_run.hpp"
#include "window_summary.hpp"

namespace hba::pyramid {
namespace {

const hba::test::Sequence& drive() {
  static const hba::test::Sequence sequence = hba::test::simulateSequence(hba::test::smallDriveConfig(16));
  return sequence;
}

std::vector<const PointCloud*> cloudsOf(const Window& window) {
  std::vector<const PointCloud*> clouds;
  for (std::size_t k = 0; k < window.count; ++k) clouds.push_back(&drive().scans[window.first + k]);
  return clouds;
}

TEST(WindowRun, PathBetweenFramesIsAlongTheLayer) {
  Layer layer;
  layer.distance_m = {0.0, 1.0, 1.5, 4.0, 4.25};
  EXPECT_EQ(pathBetweenFrames(layer, Window{1, 4}), (std::vector<double>{0.5, 2.5, 0.25}));
  EXPECT_TRUE(pathBetweenFrames(layer, Window{2, 1}).empty());
}

TEST(WindowRun, StartsFromTheWindowsFramesAndHoldsTheFirst) {
  const Layer layer = scanLayer(drive().initial);
  const Window window{5, 7};
  const ba::BaResult result = runWindowBa(layer, window, cloudsOf(window), HbaSettings().localBa());
  ASSERT_EQ(result.poses.size(), 7u);
  EXPECT_GT(result.num_planes, 0u);
  EXPECT_EQ(result.poses.front().t, layer.poses[5].t);
  EXPECT_EQ(result.poses.front().q.coeffs(), layer.poses[5].q.coeffs());
  // The same window run directly: same input poses, same path.
  const std::vector<Pose> initial(drive().initial.begin() + 5, drive().initial.begin() + 12);
  const ba::BaResult direct = ba::optimizeWindow(cloudsOf(window), initial, HbaSettings().localBa(),
                                                 pathBetweenFrames(layer, window));
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(result.poses[k].t, direct.poses[k].t) << k;
}

TEST(WindowSummary, FactorsJoinTheLayerOneFramesTheWindowAnchors) {
  Layer layer = scanLayer(drive().initial);
  for (std::size_t i = 0; i < layer.nodes.size(); ++i) layer.nodes[i] = 3 * i;
  const Window window{5, 7};
  const ba::BaResult result = runWindowBa(layer, window, cloudsOf(window), HbaSettings().localBa());
  // The default: one factor of the whole window over nodes 3 i, i = 5 .. 11.
  const WindowSummary joint = summarizeWindow(layer, window, result, HbaSettings());
  EXPECT_TRUE(joint.outcome.factors.empty());
  ASSERT_EQ(joint.outcome.shapes.size(), 1u);
  ASSERT_EQ(joint.outcome.shapes[0].nodes.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(joint.outcome.shapes[0].nodes[k], 3 * (5 + k));
  // Adjacent pairs (the paper's): frames 5-6, ..., 10-11.
  HbaSettings pairs;
  pairs.factor_pairs = FactorPairs::Adjacent;
  const WindowSummary summary = summarizeWindow(layer, window, result, pairs);
  EXPECT_TRUE(summary.outcome.shapes.empty());
  EXPECT_EQ(summary.outcome.window.first, 5u);
  EXPECT_EQ(summary.outcome.window.count, 7u);
  EXPECT_TRUE(summary.outcome.has_planes);
  ASSERT_EQ(summary.outcome.factors.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(summary.outcome.factors[k].from, 3 * (5 + k));
    EXPECT_EQ(summary.outcome.factors[k].to, 3 * (6 + k));
  }
  EXPECT_EQ(summary.planes, result.num_planes);
  EXPECT_EQ(summary.plane_points, result.num_plane_points);
  double sq = 0.0;
  for (double r : result.plane_rms_final) sq += r * r;
  EXPECT_DOUBLE_EQ(summary.sq_rms_after, sq);
  EXPECT_EQ(summary.cost_after, result.final_cost);
  EXPECT_EQ(summary.trusted, result.trusted);
}

TEST(Keyframe, KeepsThePlanePointsInTheFirstFramesCoordinates) {
  PointCloud a, b;
  a.add(Vec3f(1, 0, 0));
  a.add(Vec3f(0, 1, 0));
  b.add(Vec3f(2, 0, 0));
  b.add(Vec3f(1, 0, 3));
  const std::vector<Pose> poses{test::poseAt(10.0, 0.0, 0.0), test::poseAt(10.0, 5.0, 90.0)};
  // Only a's first point and b's second are on planes.
  const PointCloud keyframe = buildKeyframe({&a, &b}, poses, {{0}, {1}}, 0.0);
  ASSERT_EQ(keyframe.size(), 2u);
  EXPECT_LT((keyframe.points[0] - Vec3f(1, 0, 0)).norm(), 1e-6f);
  // b's point (1, 0, 3) turned by 90 degrees about z, then moved 5 m along y.
  EXPECT_LT((keyframe.points[1] - Vec3f(0, 6, 3)).norm(), 1e-6f);
  EXPECT_FALSE(keyframe.hasIntensity());
}

}  // namespace
}  // namespace hba::pyramid
