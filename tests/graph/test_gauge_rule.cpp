// The gauge rule: which node of which component is held, and how much of it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gauge_anchors.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/lie.hpp"

namespace hba::graph {
namespace {

GaugeInput between(std::size_t a, std::size_t b) { return {{a, b}, {}}; }
GaugeInput posePin(std::size_t node) { return {{node}, {PinKind::Pose, Vec3::Zero()}}; }
GaugeInput positionPin(std::size_t node, const Vec3& p) { return {{node}, {PinKind::Position, p}}; }
GaugeInput weakPrior(std::size_t node) { return {{node}, {}}; }  // not firm: pins nothing

TEST(SpreadOffLine, IsTheRootSumSquareDistanceFromTheBestLine) {
  // (+-a, 0, 0) and (0, +-b, 0) with a > b: the best line is the x axis and
  // the two points off it are b away.
  const double a = 10.0;
  const double b = 3.0;
  const std::vector<Vec3> cross = {Vec3(a, 0, 0), Vec3(-a, 0, 0), Vec3(0, b, 0), Vec3(0, -b, 0)};
  EXPECT_NEAR(spreadOffLine(cross), std::sqrt(2.0) * b, 1e-12);
  // The same after a rigid motion far from the origin.
  const Pose motion(so3Exp(Vec3(0.3, -0.7, 1.1)), Vec3(4e4, -2e4, 300));
  std::vector<Vec3> moved;
  for (const Vec3& p : cross) moved.push_back(motion * p);
  EXPECT_NEAR(spreadOffLine(moved), std::sqrt(2.0) * b, 1e-6);
}

TEST(SpreadOffLine, IsZeroForCollinearOrTooFewPoints) {
  EXPECT_EQ(spreadOffLine({}), 0.0);
  EXPECT_EQ(spreadOffLine({Vec3(1, 2, 3), Vec3(50, 0, 0)}), 0.0);
  const Vec3 direction = Vec3(1, 2, -0.5).normalized();
  std::vector<Vec3> line;
  for (const double s : {-7.0, 0.0, 2.0, 30.0}) line.push_back(Vec3(5, 5, 5) + s * direction);
  EXPECT_LT(spreadOffLine(line), 1e-6);
  EXPECT_EQ(spreadOffLine({Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}), 0.0);
}

TEST(ComponentAnchors, PriorsDecideWhichComponentsHoldANode) {
  const std::vector<GaugeInput> factors = {
      // {0, 1, 2}: a pose prior fixes everything.
      between(0, 1), between(1, 2), posePin(2),
      // {3, 4, 5}: position priors on three non-collinear nodes.
      between(3, 4), between(4, 5), positionPin(3, Vec3(0, 0, 0)), positionPin(4, Vec3(10, 0, 0)),
      positionPin(5, Vec3(10, 10, 0)),
      // {6, 7, 8}: three collinear position priors leave a rotation free.
      between(6, 7), between(7, 8), positionPin(6, Vec3(0, 0, 0)), positionPin(7, Vec3(10, 0, 0)),
      positionPin(8, Vec3(20, 0, 0)),
      // {10, 9}: one position prior.
      between(10, 9), positionPin(10, Vec3(1, 2, 3)),
      // {11, 12}: no priors at all, and {13}: a prior too weak to pin.
      between(12, 11), weakPrior(13),
      // 14 is touched by nothing.
  };
  const std::vector<GaugeAnchor> expected = {
      {6, GaugeHold::Orientation}, {9, GaugeHold::Orientation}, {11, GaugeHold::Pose}, {13, GaugeHold::Pose}};
  EXPECT_EQ(componentAnchors(15, factors, 1.0), expected);
}

TEST(ComponentAnchors, ThePriorsMustSpreadAtLeastTheSettingOffTheirLine) {
  // Three priors on a triangle whose apex is `height` off its base line.
  for (const double height : {0.5, 2.0}) {
    const std::vector<GaugeInput> factors = {between(0, 1), between(1, 2), positionPin(0, Vec3(0, 0, 0)),
                                             positionPin(1, Vec3(20, 0, 0)),
                                             positionPin(2, Vec3(10, height, 0))};
    const double spread = spreadOffLine({Vec3(0, 0, 0), Vec3(20, 0, 0), Vec3(10, height, 0)});
    EXPECT_TRUE(componentAnchors(3, factors, 0.9 * spread).empty()) << height;
    EXPECT_EQ(componentAnchors(3, factors, 1.1 * spread),
              (std::vector<GaugeAnchor>{{0, GaugeHold::Orientation}}))
        << height;
  }
}

TEST(ComponentAnchors, PriorsCountForTheComponentTheirNodeJoinsLater) {
  // The prior on node 4 comes before the factor that joins 4 to 0.
  const std::vector<GaugeInput> factors = {posePin(4), between(0, 1), between(1, 4)};
  EXPECT_TRUE(componentAnchors(5, factors, 1.0).empty());
}

// Today's rule by flood fill: the smallest node of each touched component.
std::vector<std::size_t> smallestOfEachComponent(std::size_t n, const std::vector<GaugeInput>& factors) {
  std::vector<std::vector<std::size_t>> neighbours(n);
  std::vector<bool> touched(n, false);
  for (const GaugeInput& f : factors) {
    neighbours[f.nodes[0]].push_back(f.nodes[1]);
    neighbours[f.nodes[1]].push_back(f.nodes[0]);
    touched[f.nodes[0]] = touched[f.nodes[1]] = true;
  }
  std::vector<bool> seen(n, false);
  std::vector<std::size_t> smallest;
  for (std::size_t i = 0; i < n; ++i) {
    if (!touched[i] || seen[i]) continue;
    smallest.push_back(i);
    std::vector<std::size_t> stack = {i};
    seen[i] = true;
    while (!stack.empty()) {
      const std::size_t at = stack.back();
      stack.pop_back();
      for (const std::size_t next : neighbours[at]) {
        if (seen[next]) continue;
        seen[next] = true;
        stack.push_back(next);
      }
    }
  }
  return smallest;
}

TEST(ComponentAnchors, WithoutPriorsHoldsTheSmallestNodeOfEachComponent) {
  std::mt19937 rng(37);
  std::uniform_int_distribution<std::size_t> node(0, 59);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<GaugeInput> inputs;
    for (int k = 0; k < 40; ++k) inputs.push_back(between(node(rng), node(rng)));
    std::vector<std::size_t> held;
    for (const GaugeAnchor& anchor : componentAnchors(60, inputs, 1.0)) {
      EXPECT_EQ(anchor.hold, GaugeHold::Pose);
      held.push_back(anchor.node);
    }
    EXPECT_EQ(held, smallestOfEachComponent(60, inputs)) << trial;
  }
}

}  // namespace
}  // namespace hba::graph
