// Descriptors and global registration (issue #38): two submaps of one place
// meet from any relative pose, not only z up or a small offset; submaps of
// different places do not.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/closure/feature_registration.hpp"
#include "hba/closure/point_features.hpp"
#include "hba/core/lie.hpp"
#include "neighbourhood.hpp"
#include "simulated_scans.hpp"

namespace hba::closure {
namespace {

constexpr double kVoxel = 0.5;

class Registering : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    simulation_ = new sim::Simulation(sim::prepareSimulation(test::revisitingDrive(sim::SensorModel::Vlp16)));
    scans_ = new test::LazySimulatedScans(*simulation_, 0.1);
  }
  static void TearDownTestSuite() {
    delete scans_;
    delete simulation_;
  }

  // Frames centre +- 6 merged in the centre's frame by the true poses, then
  // turned by `turn` about the sensor (the frame's origin, which the normals face).
  static PointCloud submap(std::size_t centre, const Mat3& turn = Mat3::Identity()) {
    PointCloud cloud = mergeNeighbourhood(*scans_, simulation_->truth.poses, centre,
                                          neighbourhoodFrames(centre, 6, scans_->size()), 0.1);
    for (Vec3f& p : cloud.points) p = (turn * p.cast<double>()).cast<float>();
    return cloud;
  }
  static Pose truthBetween(std::size_t from, std::size_t to) {
    return relative(simulation_->truth.poses[from], simulation_->truth.poses[to]);
  }

  static sim::Simulation* simulation_;
  static test::LazySimulatedScans* scans_;
};
sim::Simulation* Registering::simulation_ = nullptr;
test::LazySimulatedScans* Registering::scans_ = nullptr;

// Yaw 120 deg, then roll 5 and pitch -3: a tilted mount in an unrelated frame.
Mat3 anyTurn() {
  return (Eigen::AngleAxisd(120.0 * M_PI / 180.0, Vec3::UnitZ()) *
          Eigen::AngleAxisd(5.0 * M_PI / 180.0, Vec3::UnitX()) *
          Eigen::AngleAxisd(-3.0 * M_PI / 180.0, Vec3::UnitY()))
      .toRotationMatrix();
}

double degrees(const Pose& a, const Pose& b) { return so3Log(relative(a, b).q).norm() * 180.0 / M_PI; }

TEST_F(Registering, DescriptorsOfOnePlaceMatchInAnyOrientation) {
  const FeatureCloud upright = describeCloud(submap(40), kVoxel);
  const FeatureCloud turned = describeCloud(submap(40, anyTurn()), kVoxel);
  ASSERT_GT(upright.features.size(), 300u);
  ASSERT_EQ(turned.features.size(), turned.keypoints.size());
  // Each histogram: the point's own plus its neighbours', each normalised to
  // 100 (0 for a point alone in its radius).
  std::size_t complete = 0;
  for (const Fpfh& f : upright.features) {
    for (int part = 0; part < 3; ++part) {
      const float sum = f.segment<11>(part * 11).sum();
      EXPECT_NEAR(sum, 100.0F * std::round(sum / 100.0F), 0.1F);
    }
    complete += std::abs(f.sum() - 600.0F) < 0.1F ? 1 : 0;
  }
  EXPECT_GT(complete, upright.features.size() * 9 / 10);
  const auto matches = mutualMatches(turned, upright);
  std::size_t right = 0;
  for (const auto& [s, t] : matches) {
    const Vec3 moved = anyTurn().transpose() * turned.points[s].cast<double>();
    right += (moved - upright.points[t].cast<double>()).norm() < 2.0 * kVoxel ? 1 : 0;
  }
  // Most keypoints fall elsewhere after the turn's voxel grid; of those that
  // pair, many pair with their own place (by chance: a few in a thousand).
  EXPECT_GT(matches.size(), 100u);
  EXPECT_GT(static_cast<double>(right) / static_cast<double>(matches.size()), 0.15)
      << right << " of " << matches.size();
}

TEST_F(Registering, TwoPlacesMetresApartMeetFromAnUnrelatedFrame) {
  // Frames 40 and 50: 5 m apart on one street; the source turned about its sensor.
  const FeatureCloud target = describeCloud(submap(40), kVoxel);
  const FeatureCloud source = describeCloud(submap(50, anyTurn()), kVoxel);
  const Registration r = registerClouds(source, target);
  ASSERT_TRUE(r.found) << r.reason;
  const Pose expected = truthBetween(40, 50) * Pose(Mat3(anyTurn().transpose()), Vec3::Zero());
  EXPECT_LT((r.target_from_source.t - expected.t).norm(), 0.05) << r.target_from_source.t.transpose();
  EXPECT_LT(degrees(r.target_from_source, expected), 0.3);
  EXPECT_GT(r.fitness, 0.6);
  EXPECT_GE(r.inliers, 10u);
  EXPECT_LT(r.rms_m, 0.1);  // within 1.5 voxels, on a 16-beam map
}

TEST_F(Registering, TheSameInputGivesTheSameResult) {
  const FeatureCloud target = describeCloud(submap(40), kVoxel);
  const FeatureCloud source = describeCloud(submap(50, anyTurn()), kVoxel);
  const Registration a = registerClouds(source, target);
  const Registration b = registerClouds(source, target);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.target_from_source.t, b.target_from_source.t);
}

TEST_F(Registering, PlacesThatDoNotOverlapAreNotMatched) {
  // Frame 40 and frame 140: half a lap apart, different streets.
  const FeatureCloud target = describeCloud(submap(40), kVoxel);
  const FeatureCloud source = describeCloud(submap(140, anyTurn()), kVoxel);
  const Registration r = registerClouds(source, target);
  EXPECT_TRUE(!r.found || r.fitness < 0.3) << r.inliers << " inliers, fitness " << r.fitness;
}

TEST(FeatureRegistration, EmptyAndTinyCloudsAreNotFoundWithAReason) {
  const Registration r = registerClouds(FeatureCloud{}, FeatureCloud{});
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.reason.find("descriptor matches"), std::string::npos) << r.reason;
  PointCloud few;
  for (int i = 0; i < 4; ++i) few.add(Vec3f(static_cast<float>(i), 0.0F, 1.0F));
  EXPECT_TRUE(describeCloud(few, 0.5).points.empty());  // no normal without 5 neighbours
}

}  // namespace
}  // namespace hba::closure
