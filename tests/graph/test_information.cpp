#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "clamped_inverse.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/graph/information.hpp"

namespace hba::graph {
namespace {

using test::pairwiseHessian;
using test::randomPose;
using test::randomVec6;

Mat6 randomInformation(std::mt19937& rng) {
  Mat6 A;
  for (int k = 0; k < 6; ++k) A.col(k) = randomVec6(rng, 1.0, 1.0);
  return A * A.transpose() + 0.1 * Mat6::Identity();
}

double relativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

bool symmetricPositiveDefinite(const Mat6& m) {
  if (!m.allFinite() || (m - m.transpose()).norm() > 1e-9 * m.norm()) return false;
  return Eigen::SelfAdjointEigenSolver<Mat6>(m).eigenvalues().minCoeff() > 0.0;
}

TEST(RelativePoseInformation, TwoFramesMeasuredRelativeToEachOtherGiveThatInformation) {
  // A window whose only data is the relative pose of its two frames, with
  // information W: its cost is sigma^2 e^T W e so that the Fisher information
  // H / (2 sigma^2) is J^T W J, and the propagated information must be W.
  std::mt19937 rng(21);
  InformationSettings settings;
  settings.point_sigma = 0.05;
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<Pose> poses = {randomPose(rng), randomPose(rng)};
    const Mat6 W = randomInformation(rng);
    const Eigen::MatrixXd H =
        settings.point_sigma * settings.point_sigma * pairwiseHessian(poses, {{0, 1}}, W);
    const Mat6 omega = relativePoseInformation(H, poses, 0, 1, settings);
    EXPECT_LT(relativeDifference(omega, W), 1e-9);
    EXPECT_TRUE(symmetricPositiveDefinite(relativePoseInformation(H, poses, 1, 0, settings)));
  }
}

TEST(RelativePoseInformation, MatchesTheGaugeFreeCovarianceOfALinearModel) {
  // Independent route: a random linear model A x (rows orthogonal to the
  // gauge), cost |A x|^2 so H = 2 A^T A; the relative pose error's covariance
  // is J F^+ J^T with J by finite differences over all frames and F^+ the
  // pseudo-inverse of the Fisher information (valid since J is gauge-blind).
  std::mt19937 rng(22);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng), randomPose(rng), randomPose(rng)};
  const Eigen::MatrixXd N = test::gaugeBasis(poses);
  const Eigen::MatrixXd gauge_projector =
      Eigen::MatrixXd::Identity(24, 24) - N * (N.transpose() * N).inverse() * N.transpose();
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(40, 24) * gauge_projector;
  const Eigen::MatrixXd H = 2.0 * A.transpose() * A;
  InformationSettings settings;
  settings.point_sigma = 0.1;
  const Eigen::MatrixXd fisher = A.transpose() * A / (settings.point_sigma * settings.point_sigma);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition(fisher);
  decomposition.setThreshold(1e-10);
  ASSERT_EQ(decomposition.rank(), 18);  // exactly the 6-dim gauge is free
  const Eigen::MatrixXd fisher_pinv = decomposition.pseudoInverse();

  for (const auto& [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{{1, 3}, {0, 2}, {3, 0}}) {
    const Eigen::MatrixXd J = test::numericRelativeErrorJacobian(poses, a, b);
    const Mat6 expected = (J * fisher_pinv * J.transpose()).inverse();
    const Mat6 omega = relativePoseInformation(H, poses, a, b, settings);
    EXPECT_LT(relativeDifference(omega, expected), 1e-6) << a << "->" << b;
  }
}

TEST(RelativePoseInformation, ScalesWithTheInversePointVariance) {
  std::mt19937 rng(23);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng), randomPose(rng)};
  const Eigen::MatrixXd H = pairwiseHessian(poses, {{0, 1}, {1, 2}, {0, 2}}, randomInformation(rng));
  InformationSettings coarse;
  coarse.point_sigma = 0.02;
  InformationSettings fine;
  fine.point_sigma = 0.01;
  EXPECT_LT(relativeDifference(relativePoseInformation(H, poses, 0, 2, fine),
                               4.0 * relativePoseInformation(H, poses, 0, 2, coarse)),
            1e-9);
}

// A corridor along world x: frames share one orientation and the data never
// constrain relative motion along x (weight `along` on that direction).
Eigen::MatrixXd corridorHessian(const std::vector<Pose>& poses, double along) {
  Vec6 weights;
  weights << along, 1.0, 1.0, 100.0, 100.0, 100.0;
  return pairwiseHessian(poses, {{0, 1}, {1, 2}, {2, 3}, {0, 2}, {1, 3}}, Mat6(weights.asDiagonal()));
}

TEST(RelativePoseInformation, CorridorGetsAWeakFiniteWeightAlongTheFreeDirection) {
  const Mat3 heading = so3Exp(Vec3(0.0, 0.0, 0.0));
  std::vector<Pose> poses;
  for (int i = 0; i < 4; ++i) poses.emplace_back(heading, Vec3(5.0 * i, 0.0, 1.5));
  // (2, 3) does not contain the gauge frame 0: both ends carry clamped variance.
  for (const auto& [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{{0, 1}, {2, 3}}) {
    const Mat6 degenerate = relativePoseInformation(corridorHessian(poses, 0.0), poses, a, b);
    const Mat6 well_posed = relativePoseInformation(corridorHessian(poses, 1.0), poses, a, b);

    EXPECT_TRUE(symmetricPositiveDefinite(degenerate));
    const double weakest_constrained = degenerate.diagonal().tail<5>().minCoeff();
    EXPECT_LT(degenerate(0, 0), 1e-3 * weakest_constrained);
    EXPECT_LT(degenerate(0, 0), 1e-3 * well_posed(0, 0));
    // The constrained directions keep exactly the weight they would have had.
    EXPECT_LT(relativeDifference(degenerate.bottomRightCorner<5, 5>(), well_posed.bottomRightCorner<5, 5>()),
              1e-6);
  }
}

TEST(RelativePoseInformation, ZeroHessianGivesTheTinyIsotropicFallback) {
  std::mt19937 rng(24);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng), randomPose(rng)};
  InformationSettings settings;
  settings.fallback_information = 1e-5;
  const Mat6 omega = relativePoseInformation(Eigen::MatrixXd::Zero(18, 18), poses, 2, 0, settings);
  EXPECT_EQ(omega, Mat6(1e-5 * Mat6::Identity()));
}

TEST(RelativePoseInformation, SlightlyIndefiniteHessianStaysFiniteAndClose) {
  // The BA's exact Hessian of lambda_min may carry small negative eigenvalues.
  std::mt19937 rng(25);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng), randomPose(rng)};
  const Eigen::MatrixXd clean = pairwiseHessian(poses, {{0, 1}, {1, 2}}, randomInformation(rng));
  Eigen::VectorXd v = Eigen::VectorXd::Random(18).normalized();
  const Eigen::MatrixXd noisy = clean - 1e-9 * clean.norm() * v * v.transpose();
  const Mat6 omega = relativePoseInformation(noisy, poses, 0, 2);
  EXPECT_TRUE(symmetricPositiveDefinite(omega));
  EXPECT_LT(relativeDifference(omega, relativePoseInformation(clean, poses, 0, 2)), 1e-3);
}

TEST(RelativePoseInformation, RejectsBadArguments) {
  std::mt19937 rng(26);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng)};
  const Eigen::MatrixXd H = pairwiseHessian(poses, {{0, 1}}, Mat6::Identity());
  EXPECT_THROW(relativePoseInformation(H, poses, 1, 1), Error);
  EXPECT_THROW(relativePoseInformation(H, poses, 0, 2), Error);
  EXPECT_THROW(relativePoseInformation(Eigen::MatrixXd::Zero(12, 18), poses, 0, 1), Error);
  EXPECT_THROW(relativePoseInformation(Eigen::MatrixXd::Zero(18, 18), poses, 0, 1), Error);
  Eigen::MatrixXd nan = H;
  nan(3, 4) = std::nan("");
  EXPECT_THROW(relativePoseInformation(nan, poses, 0, 1), Error);
  InformationSettings bad;
  bad.point_sigma = 0.0;
  EXPECT_THROW(relativePoseInformation(H, poses, 0, 1, bad), Error);
  bad = InformationSettings{};
  bad.min_eigen_ratio = 0.0;
  EXPECT_THROW(relativePoseInformation(H, poses, 0, 1, bad), Error);
}

}  // namespace
}  // namespace hba::graph

namespace hba::graph {
namespace {

// A symmetric matrix of n rows with the given eigenvalues, in random axes.
Eigen::MatrixXd withEigenvalues(const Eigen::VectorXd& values, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const auto n = values.size();
  Eigen::MatrixXd random(n, n);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) random(r, c) = normal(rng);
  }
  const Eigen::MatrixXd axes = Eigen::HouseholderQR<Eigen::MatrixXd>(random).householderQ();
  return axes * values.asDiagonal() * axes.transpose();
}

// n eigenvalues from 1e9 down to 1e9 * 2e-6: none below a 1e-6 floor.
Eigen::VectorXd wellPosedSpectrum(Eigen::Index n) {
  Eigen::VectorXd values(n);
  for (Eigen::Index k = 0; k < n; ++k) values[k] = 1e9 * std::pow(2e-6, double(k) / double(n - 1));
  return values;
}

TEST(ClampedInverse, IsTheInverseWhereNoEigenvalueIsRaisedAndRaisesThoseBelowTheFloor) {
  std::mt19937 rng(41);
  // A window's size: eigenvalues from 1e9 down to 1e9 * 2e-6 (none below a
  // 1e-6 floor), then one at 1e-9 of the largest (raised to the floor).
  const Eigen::Index n = 312;
  Eigen::VectorXd values = wellPosedSpectrum(n);
  const Eigen::MatrixXd well = withEigenvalues(values, rng);
  const auto inverse = clampedInverse(well, 1e-6);
  ASSERT_TRUE(inverse);
  EXPECT_LT(relativeDifference(*inverse * well, Eigen::MatrixXd::Identity(n, n)), 1e-6);

  values[n - 1] = 1.0;  // 1e-9 of the largest
  const Eigen::MatrixXd weak = withEigenvalues(values, rng);
  const auto clamped = clampedInverse(weak, 1e-6);
  ASSERT_TRUE(clamped);
  const Eigen::VectorXd got = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(*clamped).eigenvalues();
  EXPECT_NEAR(got.maxCoeff(), 1.0 / (1e-6 * 1e9), 1e-6 * got.maxCoeff());  // the raised one
  EXPECT_NEAR(got.minCoeff(), 1.0 / 1e9, 1e-6 / 1e9);

  EXPECT_FALSE(clampedInverse(Eigen::MatrixXd::Zero(6, 6), 1e-6));
  EXPECT_FALSE(clampedInverse(-well, 1e-6));
}

TEST(ClampedUp, IsTheMatrixWhereNoEigenvalueIsRaisedAndTheClampedInversesInverse) {
  std::mt19937 rng(42);
  const Eigen::Index n = 60;
  Eigen::VectorXd values = wellPosedSpectrum(n);
  const Eigen::MatrixXd well = withEigenvalues(values, rng);
  const auto same = clampedUp(well, 1e-6);
  ASSERT_TRUE(same);
  EXPECT_LT(relativeDifference(*same, well), 1e-15);

  values[n - 1] = 1.0;  // 1e-9 of the largest: raised to 1e3
  values[n - 2] = 0.0;  // no information at all: raised too
  const Eigen::MatrixXd weak = withEigenvalues(values, rng);
  const auto raised = clampedUp(weak, 1e-6);
  const auto inverse = clampedInverse(weak, 1e-6);
  ASSERT_TRUE(raised && inverse);
  const Eigen::VectorXd got = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(*raised).eigenvalues();
  EXPECT_NEAR(got[0], 1e3, 1e-6 * 1e3);
  EXPECT_NEAR(got[1], 1e3, 1e-6 * 1e3);
  EXPECT_NEAR(got[2], values[n - 3], 1e-6 * values[n - 3]);
  EXPECT_LT(relativeDifference(*raised * *inverse, Eigen::MatrixXd::Identity(n, n)), 1e-6);
  // The few raised directions found alone (inverse iteration) give the
  // matrix the whole eigen-decomposition gives.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(weak);
  const Eigen::VectorXd floored = eigen.eigenvalues().cwiseMax(1e-6 * eigen.eigenvalues().maxCoeff());
  const Eigen::MatrixXd expected =
      eigen.eigenvectors() * floored.asDiagonal() * eigen.eigenvectors().transpose();
  EXPECT_LT(relativeDifference(*raised, expected), 1e-12);

  EXPECT_FALSE(clampedUp(Eigen::MatrixXd::Zero(6, 6), 1e-6));
  EXPECT_FALSE(clampedUp(-well, 1e-6));
}

}  // namespace
}  // namespace hba::graph
