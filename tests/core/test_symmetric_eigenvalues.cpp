#include "core/symmetric_eigenvalues.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace hba {
namespace {

// A random rotation: the matrices below are far from diagonal.
Mat3 randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
}

// The scatter of n points on a plane patch of extents a and b and thickness
// s, turned: its eigenvalues are n s^2 <= n b^2 <= n a^2 (for s <= b <= a).
TEST(SymmetricEigenvalues, ThePlanesCostIsExactToEpsilonOfTheLargest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double a = 0.1 + 4.0 * unit(rng);
    // Every tenth patch square (its two largest eigenvalues equal: the
    // closed form's hard case for that pair, not for the smallest), and
    // some strips as thin as they are thick (the two smallest equal).
    const double b = k % 10 == 0 ? a : a * unit(rng);
    const double s = std::min(b, 0.1 * std::pow(10.0, -4.0 * unit(rng)));  // down to 10 um thick
    const double n = 20.0 + 1000.0 * unit(rng);
    const Mat3 R = randomRotation(rng);
    const Mat3 m = R * Vec3(n * s * s, n * b * b, n * a * a).asDiagonal() * R.transpose();
    const Vec3 values = symmetricEigenvalues(m);
    ASSERT_LE(values(0), values(1));
    ASSERT_LE(values(1), values(2));
    const double largest = n * a * a;
    const Vec3 iterative = Eigen::SelfAdjointEigenSolver<Mat3>(m, Eigen::EigenvaluesOnly).eigenvalues();
    // The smallest to a few epsilon of the largest, as the iterative
    // solver's; the largest, close to the middle one, only to about 1e-8.
    EXPECT_NEAR(values(0), n * s * s, 1e-13 * largest) << k;
    EXPECT_NEAR(iterative(0), n * s * s, 1e-13 * largest) << k;
    EXPECT_NEAR(values(2), largest, 1e-7 * largest) << k;
    worst = std::max(worst, std::abs(values(0) - n * s * s) / largest);
  }
  RecordProperty("worst_smallest_error_of_largest", std::to_string(worst));
}

TEST(SymmetricEigenvalues, AsTheIterativeSolverOnTurnedMatrices) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 R = randomRotation(rng);
    const Mat3 m = R * Vec3(unit(rng), unit(rng), unit(rng)).asDiagonal() * R.transpose();
    const Vec3 iterative = Eigen::SelfAdjointEigenSolver<Mat3>(m, Eigen::EigenvaluesOnly).eigenvalues();
    EXPECT_TRUE(symmetricEigenvalues(m).isApprox(iterative, 1e-12)) << k;
  }
}

TEST(SymmetricEigenvalues, DiagonalAndDegenerateMatrices) {
  EXPECT_EQ(symmetricEigenvalues(Mat3::Zero()), Vec3::Zero());
  const Vec3 diagonal = symmetricEigenvalues(Vec3(3.0, 1.0, 2.0).asDiagonal());
  EXPECT_NEAR(diagonal(0), 1.0, 1e-14);
  EXPECT_NEAR(diagonal(1), 2.0, 1e-14);
  EXPECT_NEAR(diagonal(2), 3.0, 1e-14);
  // Points on a line: a double zero, which the closed form alone resolves
  // only to about 1e-8.
  const Vec3 d = Vec3(1.0, 2.0, 3.0).normalized();
  const Vec3 line = symmetricEigenvalues(5.0 * d * d.transpose());
  EXPECT_NEAR(line(0), 0.0, 1e-13);
  EXPECT_NEAR(line(1), 0.0, 1e-13);
  EXPECT_NEAR(line(2), 5.0, 1e-13);
}

}  // namespace
}  // namespace hba
