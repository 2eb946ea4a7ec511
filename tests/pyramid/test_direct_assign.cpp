// directAssign hands each upper pose down to the frames its keyframe stands
// for (ownFrames), read from the windows themselves, not from a stride.
#include <gtest/gtest.h>

#include "hand_made_plan.hpp"
#include "top_down.hpp"

namespace hba::pyramid {
namespace {

using test::expectNear;

std::vector<Pose> topPoses(std::size_t n) {
  std::vector<Pose> poses;
  for (std::size_t j = 0; j < n; ++j) {
    poses.push_back(test::poseAt(5.0 * static_cast<double>(j), 1.0, -7.0 * static_cast<double>(j)));
  }
  return poses;
}

TEST(DirectAssign, EachKeyframeMovesItsOwnFrames) {
  const LayerOutcome layer1 = test::handMadeLayerOutcome(test::unevenPlan());
  const std::vector<Pose> top = topPoses(3);
  const std::vector<Pose> poses = directAssign({layer1}, top);
  ASSERT_EQ(poses.size(), 14u);
  // Own frames: window 0 -> 0-2, window 1 -> 3-6, window 2 -> 7-13.
  const std::size_t window_of[14] = {0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2};
  for (std::size_t f = 0; f < 14; ++f) {
    SCOPED_TRACE(testing::Message() << "frame " << f);
    const std::size_t j = window_of[f];
    const WindowOutcome& w = layer1.windows[j];
    const std::size_t k = f - w.window.first;
    expectNear(poses[f], top[j] * relative(w.optimized.front(), w.optimized[k]));
  }
  // A window's first frame takes its keyframe's pose as it is.
  expectNear(poses[3], top[1]);
  expectNear(poses[7], top[2]);
}

TEST(DirectAssign, PosesComeDownThroughEveryLayer) {
  const LayerOutcome layer1 = test::handMadeLayerOutcome(test::unevenPlan());
  // Layer 2 holds layer 1's three keyframes, in two windows: own frames 0 and 1-2.
  const LayerOutcome layer2 = test::handMadeLayerOutcome({Window{0, 2}, Window{1, 2}});
  const std::vector<Pose> top = topPoses(2);
  const std::vector<Pose> poses = directAssign({layer1, layer2}, top);
  ASSERT_EQ(poses.size(), 14u);
  const auto& upper = layer2.windows[1].optimized;
  const Pose keyframe2 = top[1] * relative(upper[0], upper[1]);
  const auto& lower = layer1.windows[2].optimized;
  expectNear(poses[13], keyframe2 * relative(lower[0], lower[6]));
  expectNear(poses[0], top[0]);
}

TEST(DirectAssign, NoLayersBelowTheTopReturnsTheTop) {
  const std::vector<Pose> top = topPoses(4);
  const std::vector<Pose> poses = directAssign({}, top);
  ASSERT_EQ(poses.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(poses[i].t, top[i].t);
    EXPECT_EQ(poses[i].q.coeffs(), top[i].q.coeffs());
  }
}

}  // namespace
}  // namespace hba::pyramid
