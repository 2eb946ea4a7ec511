#include <gtest/gtest.h>

#include <random>

#include "core/shifted_moments.hpp"

namespace hba {
namespace {

// A thin slab of points 4000 km from the origin (UTM-like): the shifted
// sums give its thickness as well as the same slab at the origin does,
// where raw sums of squared coordinates would lose it entirely.
TEST(ShiftedMoments, KeepTheThicknessOfASlabFarFromTheOrigin) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> across(-1.0, 1.0);
  std::normal_distribution<double> thickness(0.0, 0.01);
  const Vec3 far(512345.0, 4012345.0, 120.0);
  std::vector<Vec3> slab;
  for (int i = 0; i < 500; ++i) slab.emplace_back(across(rng), across(rng), thickness(rng));

  auto covariance = [&](const Vec3& offset) {
    ShiftedMoments moments(slab.front() + offset);
    for (const Vec3& p : slab) moments.add(p + offset);
    const double n = static_cast<double>(slab.size());
    const Vec3 mean = moments.offsetSum() / n;
    return Mat3(moments.outerSum() / n - mean * mean.transpose());
  };
  const Mat3 near_cov = covariance(Vec3::Zero());
  const Mat3 far_cov = covariance(far);
  EXPECT_NEAR(near_cov(2, 2), 1e-4, 2e-5);  // the slab's thickness, 1 cm
  EXPECT_LT((far_cov - near_cov).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(far_cov, far_cov.transpose());
}

}  // namespace
}  // namespace hba
