#include <gtest/gtest.h>

#include <random>

#include "graph_test_utils.hpp"
#include "hba/core/lie.hpp"
#include "hba/core/relative_pose_error.hpp"

namespace hba::graph {
namespace {

using test::perturbWorld;
using test::randomPose;
using test::randomVec6;

TEST(RelativePoseError, VanishesAtTheMeasurement) {
  std::mt19937 rng(1);
  for (int i = 0; i < 20; ++i) {
    const Pose a = randomPose(rng);
    const Pose b = randomPose(rng);
    EXPECT_LT(relativePoseError(relative(a, b), a, b).norm(), 1e-12);
  }
}

TEST(RelativePoseError, AgreesWithSe3LogToFirstOrder) {
  std::mt19937 rng(2);
  const Pose a = randomPose(rng);
  const Pose b = randomPose(rng);
  const Pose measurement = relative(a, b);
  for (const double size : {1e-2, 1e-3}) {
    const Vec6 xi = size * randomVec6(rng, 1.0, 1.0);
    const Pose b_moved = b * se3Exp(xi);  // error pose E = Exp(xi)
    const Vec6 e = relativePoseError(measurement, a, b_moved);
    EXPECT_LT((e - xi).norm(), 2.0 * size * size);
    EXPECT_LT((e.tail<3>() - xi.tail<3>()).norm(), 1e-12);  // rotation part is exact
  }
}

TEST(RelativePoseError, JacobiansMatchCentralDifferences) {
  std::mt19937 rng(3);
  const double h = 1e-6;
  for (int trial = 0; trial < 30; ++trial) {
    const Pose a = randomPose(rng);
    const Pose b = randomPose(rng);
    // A measurement far from the poses: the Jacobians must hold for large errors.
    const Pose measurement = randomPose(rng, 5.0, 1.2);
    const RelativePoseErrorJacobians J = relativePoseErrorJacobians(measurement, a, b);
    EXPECT_LT((J.error - relativePoseError(measurement, a, b)).norm(), 1e-14);
    for (int k = 0; k < 6; ++k) {
      Vec6 d = Vec6::Zero();
      d[k] = h;
      const Vec6 numeric_from = (relativePoseError(measurement, perturbWorld(a, d), b) -
                                 relativePoseError(measurement, perturbWorld(a, -d), b)) /
                                (2 * h);
      const Vec6 numeric_to = (relativePoseError(measurement, a, perturbWorld(b, d)) -
                               relativePoseError(measurement, a, perturbWorld(b, -d))) /
                              (2 * h);
      EXPECT_LT((numeric_from - J.d_from.col(k)).norm(), 1e-6) << "trial " << trial << " k " << k;
      EXPECT_LT((numeric_to - J.d_to.col(k)).norm(), 1e-6) << "trial " << trial << " k " << k;
    }
  }
}

TEST(RelativePoseError, IsBlindToOneRigidMotionOfBothPoses) {
  // The BA Hessian's null space (a global motion) must not move the residual:
  // J_a n_a + J_b n_b = 0 for every gauge direction.
  std::mt19937 rng(4);
  const std::vector<Pose> poses = {randomPose(rng), randomPose(rng)};
  const Pose measurement = randomPose(rng, 2.0, 0.5);
  const auto J = relativePoseErrorJacobians(measurement, poses[0], poses[1]);
  Eigen::MatrixXd both(6, 12);
  both << J.d_from, J.d_to;
  EXPECT_LT((both * test::gaugeBasis(poses)).norm(), 1e-9);

  const Pose motion = randomPose(rng);
  const Vec6 moved = relativePoseError(measurement, motion * poses[0], motion * poses[1]);
  EXPECT_LT((moved - J.error).norm(), 1e-9);
}

}  // namespace
}  // namespace hba::graph
