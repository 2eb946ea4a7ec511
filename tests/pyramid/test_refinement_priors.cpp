// The closure stage's priors as refinement terms: on a block of frames, and
// on rigid groups (a frame's position carried by its group's pose).
#include <gtest/gtest.h>

#include "hba/core/lie.hpp"
#include "refinement_priors.hpp"

namespace hba::pyramid {
namespace {

graph::PositionPriorFactor prior(std::size_t node, const Vec3& position, double sigma) {
  graph::PositionPriorFactor f;
  f.node = node;
  f.position = position;
  f.information = Mat3::Identity() / (sigma * sigma);
  return f;
}

std::vector<Pose> turningPath(std::size_t frames) {
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < frames; ++i) {
    const double a = 0.1 * static_cast<double>(i);
    poses.emplace_back(so3Exp(Vec3(0.01 * a, 0.0, a)), Vec3(10.0 * std::sin(a), 10.0 * (1.0 - std::cos(a)), 0.1 * a));
  }
  return poses;
}

TEST(RefinementPriors, BlockTermsAreTheBlocksPriorsInPlaneCostUnits) {
  const std::vector<graph::PositionPriorFactor> priors{prior(2, Vec3(1, 2, 3), 0.5), prior(5, Vec3(4, 5, 6), 0.5),
                                                       prior(9, Vec3(7, 8, 9), 2.0)};
  const ba::PositionPriors terms = blockPriors(priors, 4, 10, 0.02);
  ASSERT_EQ(terms.terms().size(), 2u);
  EXPECT_EQ(terms.terms()[0].frame, 1u);
  EXPECT_EQ(terms.terms()[1].frame, 5u);
  EXPECT_EQ(terms.terms()[1].position, Vec3(7, 8, 9));
  EXPECT_NEAR(terms.terms()[0].weight(0, 0), 0.02 * 0.02 / 0.25, 1e-15);
  EXPECT_NEAR(terms.terms()[1].weight(2, 2), 0.02 * 0.02 / 4.0, 1e-15);
  EXPECT_TRUE(terms.terms()[0].offset.isZero());
}

// A group's term, evaluated at the group's pose, is the frame's own error;
// moving the group rigidly carries the frame's position with it.
TEST(RefinementPriors, GroupTermsFollowTheirFrameInsideTheGroup) {
  const std::vector<Pose> poses = turningPath(12);
  const std::vector<std::size_t> group_first{0, 4, 8};
  const Vec3 off(0.3, -0.2, 0.1);
  const std::vector<graph::PositionPriorFactor> priors{prior(6, poses[6].t + off, 1.0),
                                                       prior(11, poses[11].t, 1.0), prior(0, poses[0].t, 1.0)};
  const ba::PositionPriors terms = groupPriors(priors, group_first, poses, 0.02);
  ASSERT_EQ(terms.terms().size(), 3u);
  EXPECT_EQ(terms.terms()[0].frame, 1u);
  EXPECT_EQ(terms.terms()[1].frame, 2u);
  EXPECT_EQ(terms.terms()[2].frame, 0u);
  EXPECT_LT((ba::PositionPriors::error(terms.terms()[0], poses[4]) + off).norm(), 1e-12);
  EXPECT_LT(ba::PositionPriors::error(terms.terms()[1], poses[8]).norm(), 1e-12);

  const Pose move(so3Exp(Vec3(0.0, 0.2, 0.4)), Vec3(1.0, 2.0, -1.0));
  const Pose group_moved = move * poses[4];
  const Vec3 frame_moved = (move * poses[6]).t;
  EXPECT_LT((ba::PositionPriors::error(terms.terms()[0], group_moved) - (frame_moved - priors[0].position)).norm(),
            1e-12);
}

}  // namespace
}  // namespace hba::pyramid
