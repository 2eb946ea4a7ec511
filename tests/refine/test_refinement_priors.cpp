// The closure stage's priors as refinement terms on a block of frames.
#include <gtest/gtest.h>

#include "refine/refinement_priors.hpp"

namespace hba::refine {
namespace {

graph::PositionPriorFactor prior(std::size_t node, const Vec3& position, double sigma) {
  graph::PositionPriorFactor f;
  f.node = node;
  f.position = position;
  f.information = Mat3::Identity() / (sigma * sigma);
  return f;
}

TEST(RefinementPriors, BlockTermsAreTheBlocksPriorsInPlaneCostUnits) {
  const std::vector<graph::PositionPriorFactor> priors{
      prior(2, Vec3(1, 2, 3), 0.5), prior(5, Vec3(4, 5, 6), 0.5), prior(9, Vec3(7, 8, 9), 2.0)};
  const ba::PositionPriors terms = blockPriors(priors, 4, 10, 0.02);
  ASSERT_EQ(terms.terms().size(), 2u);
  EXPECT_EQ(terms.terms()[0].frame, 1u);
  EXPECT_EQ(terms.terms()[1].frame, 5u);
  EXPECT_EQ(terms.terms()[1].position, Vec3(7, 8, 9));
  EXPECT_NEAR(terms.terms()[0].weight(0, 0), 0.02 * 0.02 / 0.25, 1e-15);
  EXPECT_NEAR(terms.terms()[1].weight(2, 2), 0.02 * 0.02 / 4.0, 1e-15);
  EXPECT_TRUE(terms.terms()[0].offset.isZero());
}

}  // namespace
}  // namespace hba::refine
