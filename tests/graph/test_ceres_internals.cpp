// The Ceres pieces of the pose graph: the manifold, the whitened cost and
// its Jacobians, the square root of an information matrix, the gauge anchors.
#include <gtest/gtest.h>

#include <random>

#include "gauge_anchors.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "pose_block.hpp"
#include "relative_pose_cost.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

using test::perturbWorld;
using test::randomPose;
using test::randomVec6;
using RowMajor6x7 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;
using RowMajor7x6 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;

Mat6 randomInformation(std::mt19937& rng) {
  Mat6 A = Mat6::Zero();
  for (int k = 0; k < 6; ++k) A.col(k) = randomVec6(rng, 1.0, 1.0);
  return A * A.transpose() + 0.1 * Mat6::Identity();
}

TEST(WorldPoseManifold, PlusIsTheBaPerturbationAndMinusInvertsIt) {
  std::mt19937 rng(5);
  const WorldPoseManifold manifold;
  for (int i = 0; i < 20; ++i) {
    const Pose pose = randomPose(rng);
    const Vec6 delta = randomVec6(rng, 1.0, 0.5);
    const PoseBlock x = toPoseBlock(pose);
    PoseBlock moved{};
    ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), moved.data()));
    const Pose expected = perturbWorld(pose, delta);
    const Pose got = poseFromBlock(moved.data());
    EXPECT_LT((got.t - expected.t).norm(), 1e-12);
    EXPECT_LT(got.q.angularDistance(expected.q), 1e-12);

    Vec6 back;
    ASSERT_TRUE(manifold.Minus(moved.data(), x.data(), back.data()));
    EXPECT_LT((back - delta).norm(), 1e-10);
  }
}

TEST(WorldPoseManifold, JacobiansMatchDifferencesAndInvertEachOther) {
  std::mt19937 rng(6);
  const WorldPoseManifold manifold;
  const PoseBlock x = toPoseBlock(randomPose(rng));
  RowMajor7x6 plus_jacobian;
  RowMajor6x7 minus_jacobian;
  ASSERT_TRUE(manifold.PlusJacobian(x.data(), plus_jacobian.data()));
  ASSERT_TRUE(manifold.MinusJacobian(x.data(), minus_jacobian.data()));
  EXPECT_LT((minus_jacobian * plus_jacobian - Mat6::Identity()).norm(), 1e-12);

  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vec6 d = Vec6::Zero();
    d[k] = h;
    PoseBlock plus{}, minus{};
    const Vec6 minus_d = -d;
    manifold.Plus(x.data(), d.data(), plus.data());
    manifold.Plus(x.data(), minus_d.data(), minus.data());
    for (int r = 0; r < 7; ++r) {
      EXPECT_NEAR((plus[r] - minus[r]) / (2 * h), plus_jacobian(r, k), 1e-8);
    }
  }
}

TEST(RelativePoseCost, TangentJacobiansMatchCentralDifferences) {
  std::mt19937 rng(7);
  const WorldPoseManifold manifold;
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const Mat6 S = squareRootInformation(randomInformation(rng));
    const RelativePoseCost cost(randomPose(rng, 3.0, 1.0), S);
    PoseBlock blocks[2] = {toPoseBlock(randomPose(rng)), toPoseBlock(randomPose(rng))};
    const double* params[2] = {blocks[0].data(), blocks[1].data()};
    Vec6 residual;
    RowMajor6x7 ambient[2];
    double* jacobians[2] = {ambient[0].data(), ambient[1].data()};
    ASSERT_TRUE(cost.Evaluate(params, residual.data(), jacobians));

    for (int block = 0; block < 2; ++block) {
      RowMajor7x6 lift;
      manifold.PlusJacobian(blocks[block].data(), lift.data());
      const Mat6 tangent = ambient[block] * lift;  // what Ceres' LM solves with
      for (int k = 0; k < 6; ++k) {
        Vec6 d = Vec6::Zero();
        d[k] = h;
        const Vec6 minus_d = -d;
        PoseBlock moved[2] = {blocks[0], blocks[1]};
        Vec6 r_plus, r_minus;
        manifold.Plus(blocks[block].data(), d.data(), moved[block].data());
        const double* p_plus[2] = {moved[0].data(), moved[1].data()};
        cost.Evaluate(p_plus, r_plus.data(), nullptr);
        manifold.Plus(blocks[block].data(), minus_d.data(), moved[block].data());
        const double* p_minus[2] = {moved[0].data(), moved[1].data()};
        cost.Evaluate(p_minus, r_minus.data(), nullptr);
        const Vec6 numeric = (r_plus - r_minus) / (2 * h);
        EXPECT_LT((numeric - tangent.col(k)).norm(), 1e-6 * (1.0 + numeric.norm()));
      }
    }
  }
}

TEST(SquareRootInformation, ReproducesDefiniteAndSemiDefiniteInformation) {
  std::mt19937 rng(8);
  const Mat6 definite = randomInformation(rng);
  const Mat6 S = squareRootInformation(definite);
  EXPECT_LT((S.transpose() * S - definite).norm(), 1e-10 * definite.norm());

  Mat6 singular = Mat6::Zero();
  singular.diagonal() << 4.0, 0.0, 1.0, 0.0, 9.0, 2.0;  // two unconstrained directions
  const Mat6 Ss = squareRootInformation(singular);
  EXPECT_TRUE(Ss.allFinite());
  EXPECT_LT((Ss.transpose() * Ss - singular).norm(), 1e-12);
}

TEST(SquareRootInformation, RejectsIndefiniteAndNonFiniteInformation) {
  Mat6 indefinite = Mat6::Identity();
  indefinite(2, 2) = -0.5;
  EXPECT_THROW(squareRootInformation(indefinite), Error);
  Mat6 nan = Mat6::Identity();
  nan(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(squareRootInformation(nan), Error);
}

TEST(GaugeAnchors, OneSmallestNodePerConnectedComponent) {
  auto factor = [](std::size_t from, std::size_t to) {
    RelativePoseFactor f;
    f.from = from;
    f.to = to;
    return f;
  };
  // Components {1, 2, 5} and {3, 6}; nodes 0 and 4 untouched.
  const std::vector<RelativePoseFactor> factors = {factor(5, 2), factor(6, 3), factor(2, 1)};
  EXPECT_EQ(gaugeAnchors(7, factors), (std::vector<std::size_t>{1, 3}));
  EXPECT_TRUE(gaugeAnchors(4, {}).empty());
}

}  // namespace
}  // namespace hba::graph
