#include <gtest/gtest.h>

#include "hba/closure/frame_priors.hpp"
#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

// Odometry at 10 Hz driving +x at 5 m/s.
Trajectory straightDrive(std::size_t frames) {
  Trajectory t;
  for (std::size_t k = 0; k < frames; ++k) {
    t.poses.emplace_back(Quat::Identity(), Vec3(0.5 * static_cast<double>(k), 0.0, 0.0));
    t.stamps.push_back(100.0 + 0.1 * static_cast<double>(k));
  }
  return t;
}

io::TimedPosition at(double stamp, const Vec3& position, double sigma) {
  io::TimedPosition p;
  p.stamp = stamp;
  p.position = position;
  p.sigma = Vec3::Constant(sigma);
  return p;
}

TEST(FramePriors, APriorBetweenScansGoesToTheNearestMovedByTheOdometry) {
  const Trajectory odometry = straightDrive(20);
  // At t = 100.53 the vehicle is at x = 2.65 (by the odometry); the prior
  // says 12.65 (a frame 10 m off). Nearest frame: 5 (t = 100.5, x = 2.5).
  const FramePriors p = attachPriors({at(100.53, Vec3(12.65, 1.0, 0.0), 0.5)}, odometry, 0.2);
  ASSERT_EQ(p.factors.size(), 1u);
  EXPECT_EQ(p.factors[0].node, 5u);
  EXPECT_TRUE(p.factors[0].position.isApprox(Vec3(12.5, 1.0, 0.0), 1e-9));
  EXPECT_TRUE(p.factors[0].information.isApprox(Mat3::Identity() * 4.0));
}

TEST(FramePriors, PriorsAwayFromEveryScanAreCounted) {
  const Trajectory odometry = straightDrive(20);
  const FramePriors p =
      attachPriors({at(90.0, Vec3::Zero(), 1.0), at(100.0, Vec3::Zero(), 1.0), at(102.3, Vec3::Zero(), 1.0)},
                   odometry, 0.2);
  EXPECT_EQ(p.factors.size(), 1u);
  EXPECT_EQ(p.outside, 2u);
}

TEST(FramePriors, NeedStamps) {
  Trajectory odometry = straightDrive(5);
  odometry.stamps.clear();
  EXPECT_THROW(attachPriors({at(0.0, Vec3::Zero(), 1.0)}, odometry, 0.2), Error);
}

}  // namespace
}  // namespace hba::closure
