#include <gtest/gtest.h>

#include <random>
#include <set>

#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/graph/window_factors.hpp"

namespace hba::graph {
namespace {

using test::randomPose;
using test::randomVec6;

struct Window {
  std::vector<Pose> poses;
  Eigen::MatrixXd hessian;
};

// K frames whose Hessian comes from relative measurements between all pairs.
Window makeWindow(std::mt19937& rng, std::size_t count) {
  Window w;
  for (std::size_t k = 0; k < count; ++k) w.poses.push_back(randomPose(rng, 5.0, 0.5));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) pairs.emplace_back(i, j);
  }
  Vec6 weights;
  weights << 400.0, 300.0, 200.0, 5e4, 4e4, 3e4;
  w.hessian = test::pairwiseHessian(w.poses, pairs, Mat6(weights.asDiagonal()));
  return w;
}

std::set<std::pair<std::size_t, std::size_t>> nodePairs(const std::vector<RelativePoseFactor>& fs) {
  std::set<std::pair<std::size_t, std::size_t>> out;
  for (const RelativePoseFactor& f : fs) out.emplace(f.from, f.to);
  return out;
}

TEST(WindowFactors, PairChoicesMapWindowFramesToLayerOneNodes) {
  std::mt19937 rng(31);
  const Window w = makeWindow(rng, 4);
  const std::vector<std::size_t> nodes = {0, 9, 18, 27};  // frames of layer 3 with s = 3

  using Pairs = std::set<std::pair<std::size_t, std::size_t>>;
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::Adjacent)),
            (Pairs{{0, 9}, {9, 18}, {18, 27}}));
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::FromFirst)),
            (Pairs{{0, 9}, {0, 18}, {0, 27}}));
  EXPECT_EQ(nodePairs(windowFactors(w.hessian, w.poses, nodes, FactorPairs::AllPairs)),
            (Pairs{{0, 9}, {0, 18}, {0, 27}, {9, 18}, {9, 27}, {18, 27}}));
}

TEST(WindowFactors, MeasurementsAndInformationMatchThePerPairFunctions) {
  std::mt19937 rng(32);
  const Window w = makeWindow(rng, 5);
  const std::vector<std::size_t> nodes = {10, 11, 12, 13, 14};
  const auto factors = windowFactors(w.hessian, w.poses, nodes, FactorPairs::AllPairs);
  ASSERT_EQ(factors.size(), 10u);
  for (const RelativePoseFactor& f : factors) {
    const std::size_t a = f.from - 10;
    const std::size_t b = f.to - 10;
    const Pose expected = relative(w.poses[a], w.poses[b]);
    EXPECT_LT((f.measurement.t - expected.t).norm(), 1e-12);
    EXPECT_LT(f.measurement.q.angularDistance(expected.q), 1e-12);
    const Mat6 information = relativePoseInformation(w.hessian, w.poses, a, b);
    EXPECT_LT((f.information - information).norm(), 1e-9 * information.norm());
  }
}

TEST(WindowFactors, PoseGraphOfAWindowRestoresItsOptimizedShape) {
  // Factors from one window, initial poses disturbed: the graph must bring the
  // window's relative poses back exactly (first frame fixed).
  std::mt19937 rng(33);
  const Window w = makeWindow(rng, 6);
  std::vector<std::size_t> nodes(6);
  for (std::size_t k = 0; k < 6; ++k) nodes[k] = 2 * k;  // odd nodes untouched
  std::vector<Pose> initial(11);
  for (std::size_t k = 0; k < 6; ++k) {
    initial[nodes[k]] = k == 0 ? w.poses[0] : w.poses[k] * se3Exp(randomVec6(rng, 0.5, 0.1));
  }
  for (const FactorPairs pairs : {FactorPairs::Adjacent, FactorPairs::AllPairs}) {
    PoseGraphSettings settings;
    settings.function_tolerance = 1e-16;
    const PoseGraphResult result =
        optimizePoseGraph(initial, windowFactors(w.hessian, w.poses, nodes, pairs), settings);
    for (std::size_t k = 0; k < 6; ++k) {
      EXPECT_LT((result.poses[nodes[k]].t - w.poses[k].t).norm(), 1e-6) << k;
      EXPECT_LT(result.poses[nodes[k]].q.angularDistance(w.poses[k].q), 1e-6) << k;
    }
  }
}

TEST(WindowFactors, RejectsInconsistentArguments) {
  std::mt19937 rng(34);
  const Window w = makeWindow(rng, 3);
  EXPECT_THROW(windowFactors(w.hessian, w.poses, {0, 1}, FactorPairs::Adjacent), Error);
  EXPECT_THROW(windowFactors(w.hessian, w.poses, {0, 4, 4}, FactorPairs::Adjacent), Error);
  const std::vector<Pose> too_few(w.poses.begin(), w.poses.begin() + 2);
  EXPECT_THROW(windowFactors(w.hessian, too_few, {0, 1}, FactorPairs::Adjacent), Error);
}

}  // namespace
}  // namespace hba::graph
