// buildUpperLayer reads each window's own first frame: keyframe j stands for
// window j, whatever the spacing of the windows.
#include <gtest/gtest.h>

#include "hand_made_plan.hpp"
#include "upper_layer.hpp"

namespace hba::pyramid {
namespace {

using test::expectNear;

Layer lowerLayer(std::size_t frames) {
  Layer lower;
  for (std::size_t i = 0; i < frames; ++i) {
    lower.nodes.push_back(10 * i);  // as if the lower layer were layer 2
    lower.distance_m.push_back(1.5 * static_cast<double>(i));
    lower.poses.push_back(test::poseAt(static_cast<double>(i), 0.0, 0.0));
  }
  return lower;
}

TEST(UpperLayer, KeyframesAreAnchoredAtTheirWindowsFirstFrames) {
  const LayerOutcome outcome = test::handMadeLayerOutcome(test::unevenPlan());
  const Layer upper = buildUpperLayer(lowerLayer(14), outcome, nullptr);
  EXPECT_EQ(upper.nodes, (std::vector<std::size_t>{0, 30, 70}));
  EXPECT_EQ(upper.distance_m, (std::vector<double>{0.0, 4.5, 10.5}));
  EXPECT_EQ(upper.keyframes.get(), nullptr);
}

TEST(UpperLayer, PosesChainThroughEachWindowsOwnSpacing) {
  const LayerOutcome outcome = test::handMadeLayerOutcome(test::unevenPlan());
  const Layer upper = buildUpperLayer(lowerLayer(14), outcome, nullptr);
  ASSERT_EQ(upper.poses.size(), 3u);
  const auto& w0 = outcome.windows[0].optimized;
  const auto& w1 = outcome.windows[1].optimized;
  // Keyframe 0 is its window's first frame; window 1 starts at frame 3 of
  // window 0, window 2 at frame 4 of window 1.
  expectNear(upper.poses[0], w0[0]);
  const Pose second = w0[0] * relative(w0[0], w0[3]);
  expectNear(upper.poses[1], second);
  expectNear(upper.poses[2], second * relative(w1[0], w1[4]));
}

TEST(UpperLayer, OneWindowGivesOneKeyframe) {
  const LayerOutcome outcome = test::handMadeLayerOutcome({Window{0, 5}});
  const Layer upper = buildUpperLayer(lowerLayer(5), outcome, nullptr);
  ASSERT_EQ(upper.poses.size(), 1u);
  expectNear(upper.poses[0], outcome.windows[0].optimized[0]);
}

}  // namespace
}  // namespace hba::pyramid
