#include <gtest/gtest.h>

#include <random>

#include "hba/core/lie.hpp"

namespace hba {
namespace {

Vec3 randomVec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

TEST(Lie, So3ExpLogRoundTrip) {
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Vec3 phi = randomVec(rng, 1.7);
    EXPECT_LT((so3Log(so3Exp(phi)) - phi).norm(), 1e-10);
  }
  EXPECT_LT(so3Log(Mat3::Identity()).norm(), 1e-15);
}

TEST(Lie, So3ExpMatchesAngleAxis) {
  const Vec3 axis = Vec3(1, 2, 3).normalized();
  const Mat3 expected = Eigen::AngleAxisd(0.3, axis).toRotationMatrix();
  EXPECT_LT((so3Exp(0.3 * axis) - expected).norm(), 1e-12);
}

TEST(Lie, Se3ExpLogRoundTrip) {
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    Vec6 xi;
    xi << randomVec(rng, 5.0), randomVec(rng, 1.5);
    EXPECT_LT((se3Log(se3Exp(xi)) - xi).norm(), 1e-9);
  }
}

TEST(Lie, LeftJacobianMatchesFiniteDifferences) {
  // Exp(phi + d) ~= Exp(J_l(phi) d) Exp(phi) for small d.
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    const Vec3 phi = randomVec(rng, 1.2);
    const Mat3 J = so3LeftJacobian(phi);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Vec3 d = Vec3::Zero();
      d[k] = h;
      const Vec3 numeric = so3Log(Mat3(so3Exp(phi + d) * so3Exp(phi).transpose())) / h;
      EXPECT_LT((numeric - J.col(k)).norm(), 1e-5);
    }
    EXPECT_LT((so3LeftJacobianInverse(phi) * J - Mat3::Identity()).norm(), 1e-10);
  }
}

TEST(Pose, ComposeAndInverse) {
  const Pose a(so3Exp(Vec3(0.1, -0.2, 0.3)), Vec3(1, 2, 3));
  const Pose b(so3Exp(Vec3(-0.4, 0.1, 0.2)), Vec3(-2, 0.5, 1));
  const Vec3 p(0.3, -0.7, 2.0);
  EXPECT_LT(((a * b) * p - a * (b * p)).norm(), 1e-12);
  EXPECT_LT(((a.inverse() * a) * p - p).norm(), 1e-12);
  EXPECT_LT((relative(a, b).matrix() - a.matrix().inverse() * b.matrix()).norm(), 1e-12);
  EXPECT_LT((Pose::fromMatrix(a.matrix()).matrix() - a.matrix()).norm(), 1e-12);
}

TEST(Pose, PathLength) {
  std::vector<Pose> poses(3);
  poses[1].t = Vec3(3, 4, 0);
  poses[2].t = Vec3(3, 4, 2);
  EXPECT_DOUBLE_EQ(pathLength(poses), 7.0);
  EXPECT_DOUBLE_EQ(pathLength({}), 0.0);
}

// The largest position and orientation changes may come from different poses.
TEST(Pose, LargestChangeTakesEachMaximumOverAllPoses) {
  std::vector<Pose> before(3), after(3);
  after[0].t = Vec3(0.0, 0.3, 0.4);
  after[2] = Pose(so3Exp(Vec3(0.0, 0.0, 10.0 * M_PI / 180.0)), Vec3(0.1, 0.0, 0.0));
  const PoseChange change = largestChange(before, after);
  EXPECT_NEAR(change.translation_m, 0.5, 1e-12);
  EXPECT_NEAR(change.rotation_deg, 10.0, 1e-9);
  EXPECT_EQ(largestChange(before, before).translation_m, 0.0);
}

}  // namespace
}  // namespace hba
