// A layer's pass over a hand-made uneven plan: the same per window as each
// window's BA run alone, whatever the batches, and the report and the
// keyframes follow the plan.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <memory>

#include "bottom_up.hpp"
#include "hba/core/error.hpp"
#include "hba/settings/settings.hpp"
#include "keyframe.hpp"
#include "simulated_sequence.hpp"
#include "timed_clouds.hpp"
#include "upper_layer.hpp"
#include "window_run.hpp"

namespace hba::pyramid {
namespace {

const hba::test::Sequence& drive() {
  static const hba::test::Sequence sequence = hba::test::simulateSequence(hba::test::smallDriveConfig(24));
  return sequence;
}

// No common stride: windows start at 0, 5, 10 and 14.
const std::vector<Window> kUneven{{0, 8}, {5, 8}, {10, 6}, {14, 10}};

struct LayerRun {
  LayerOutcome outcome;
  std::vector<PointCloud> keyframes;
};

// With `keyframe_batches` the layer batches like an upper layer: one window
// per thread.
LayerRun optimizeUneven(int threads, bool keyframe_batches) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  const HbaSettings settings;
  const io::MemoryScanSource memory(drive().scans);
  const TimedClouds scans(memory, settings.scan_voxel);
  Layer layer = scanLayer(drive().initial);
  if (keyframe_batches) layer.keyframes = std::make_unique<io::CloudStore>(0);
  const io::CloudStore next(kUneven.size());
  StageTimes times;
  LayerRun run;
  run.outcome =
      optimizeLayer(layer, scans, kUneven, settings.localBa(), settings, &next, 0.2, times, "test layer");
  for (std::size_t j = 0; j < kUneven.size(); ++j) run.keyframes.push_back(next.load(j));
  return run;
}

const LayerRun& unevenRun() {
  static const LayerRun run = optimizeUneven(2, false);  // one batch
  return run;
}

TEST(OptimizeLayer, EachWindowGetsWhatItsOwnBaGives) {
  const HbaSettings settings;
  const io::MemoryScanSource memory(drive().scans);
  const TimedClouds scans(memory, settings.scan_voxel);
  const Layer layer = scanLayer(drive().initial);
  const LayerRun& run = unevenRun();
  ASSERT_EQ(run.outcome.windows.size(), kUneven.size());
  std::size_t planes = 0;
  for (std::size_t j = 0; j < kUneven.size(); ++j) {
    SCOPED_TRACE(testing::Message() << "window " << j);
    std::vector<PointCloud> held;
    for (std::size_t k = 0; k < kUneven[j].count; ++k)
      held.push_back(scans.source().load(kUneven[j].first + k));
    std::vector<const PointCloud*> clouds;
    for (const PointCloud& cloud : held) clouds.push_back(&cloud);
    const ba::BaResult alone = runWindowBa(layer, kUneven[j], clouds, settings.localBa());
    const WindowOutcome& window = run.outcome.windows[j];
    EXPECT_EQ(window.window.first, kUneven[j].first);
    EXPECT_EQ(window.window.count, kUneven[j].count);
    ASSERT_EQ(window.optimized.size(), alone.poses.size());
    for (std::size_t k = 0; k < alone.poses.size(); ++k) {
      EXPECT_EQ(window.optimized[k].t, alone.poses[k].t) << "frame " << k;
      EXPECT_EQ(window.optimized[k].q.coeffs(), alone.poses[k].q.coeffs()) << "frame " << k;
    }
    // The default: one factor of the window's whole shape, over its frames.
    EXPECT_TRUE(window.factors.empty());
    ASSERT_EQ(window.shapes.size(), 1u);
    EXPECT_EQ(window.shapes[0].nodes.size(), kUneven[j].count);
    EXPECT_EQ(window.shapes[0].nodes.front(), kUneven[j].first);
    // Keyframe j is window j's plane points (stored as floats, exactly).
    const PointCloud keyframe = buildKeyframe(clouds, alone.poses, alone.plane_point_indices, 0.2);
    ASSERT_EQ(run.keyframes[j].size(), keyframe.size());
    EXPECT_GT(keyframe.size(), 0u);
    for (std::size_t i = 0; i < keyframe.size(); ++i) {
      ASSERT_EQ(run.keyframes[j].points[i], keyframe.points[i]) << "point " << i;
    }
    planes += alone.num_planes;
  }
  EXPECT_EQ(run.outcome.report.planes, planes);
}

TEST(OptimizeLayer, ReportCountsThePlansWindowsAndEveryFramesPointsOnce) {
  const HbaSettings settings;
  const io::MemoryScanSource memory(drive().scans);
  const TimedClouds scans(memory, settings.scan_voxel);
  std::size_t points = 0;
  for (std::size_t i = 0; i < scans.source().size(); ++i) points += scans.source().load(i).size();
  const LayerReport& report = unevenRun().outcome.report;
  EXPECT_EQ(report.frames, 24u);
  EXPECT_EQ(report.windows, 4u);
  EXPECT_EQ(report.cloud_points, points);
  EXPECT_GT(report.rms_before, report.rms_after);
}

TEST(OptimizeLayer, OneWindowBatchesGiveTheSameAsOneBatch) {
  // One thread, upper-layer batching: four batches of one window each, the
  // clouds of earlier windows dropped as the batches move on.
  const LayerRun small = optimizeUneven(1, true);
  const LayerRun& one = unevenRun();
  for (std::size_t j = 0; j < kUneven.size(); ++j) {
    for (std::size_t k = 0; k < kUneven[j].count; ++k) {
      EXPECT_EQ(small.outcome.windows[j].optimized[k].t, one.outcome.windows[j].optimized[k].t);
      EXPECT_EQ(small.outcome.windows[j].optimized[k].q.coeffs(),
                one.outcome.windows[j].optimized[k].q.coeffs());
    }
    EXPECT_EQ(small.keyframes[j].size(), one.keyframes[j].size());
  }
  EXPECT_EQ(small.outcome.report.cloud_points, one.outcome.report.cloud_points);
  EXPECT_EQ(small.outcome.report.planes, one.outcome.report.planes);
}

TEST(OptimizeLayer, TheUpperLayerFollowsTheUnevenPlan) {
  const Layer lower = scanLayer(drive().initial);
  const Layer upper = buildUpperLayer(lower, unevenRun().outcome, nullptr);
  EXPECT_EQ(upper.nodes, (std::vector<std::size_t>{0, 5, 10, 14}));
  ASSERT_EQ(upper.poses.size(), 4u);
  const auto& w2 = unevenRun().outcome.windows[2].optimized;
  // Window 3 starts 4 frames into window 2.
  const Pose expected = upper.poses[2] * relative(w2[0], w2[4]);
  EXPECT_LT((upper.poses[3].t - expected.t).norm(), 1e-12);
}

TEST(OptimizeLayer, RejectsAPlanThatDoesNotCoverTheLayer) {
  const HbaSettings settings;
  const io::MemoryScanSource memory(drive().scans);
  const TimedClouds scans(memory, settings.scan_voxel);
  StageTimes times;
  EXPECT_THROW(optimizeLayer(scanLayer(drive().initial), scans, {{0, 8}, {5, 8}}, settings.localBa(),
                             settings, nullptr, 0.2, times, "test layer"),
               Error);
}

}  // namespace
}  // namespace hba::pyramid
