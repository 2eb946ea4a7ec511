// Sensor model: returns lie on the surfaces they hit, noise and dropout
// follow their settings, patterns match their presets.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/sim/sensor.hpp"
#include "sim_test_world.hpp"

namespace hba::sim {
namespace {

TEST(SimSensor, NoiseFreeReturnsLieOnTheSurfacesTheyHit) {
  const Simulation& s = test::smallSimulation();
  for (SensorModel model : {SensorModel::Vlp16, SensorModel::Livox}) {
    SensorConfig config = sensorPreset(model);
    config.range_noise = 0.0;
    config.dropout = 0.0;
    for (std::size_t frame : {0u, 37u, 90u}) {
      const Pose& pose = s.truth.poses[frame];
      const auto returns = scanReturns(s.world, pose, config, 1, frame);
      ASSERT_GT(returns.size(), 2000u) << hba::toString(model);
      double worst = 0.0;
      for (const Return& r : returns) {
        worst = std::max(worst, s.world.distanceToPrimitive(r.primitive, pose * r.point));
        EXPECT_NEAR(r.point.norm(), r.true_range, 1e-9);
      }
      EXPECT_LT(worst, 1e-6) << hba::toString(model) << " frame " << frame;
    }
  }
}

// A raw sweep: each return measured from where the sensor is when it fires,
// in that instant's frame, with its time; the firing order is the sensor's.
TEST(SimSensor, RawSweepReturnsLieOnTheSurfacesFromTheMovingSensor) {
  const Simulation& s = test::smallSimulation();
  const double period = 0.1;
  // The truth's motion from frame 37 on, at the speed of its frames.
  const double start = s.truth.stamps[37];
  const SweepMotion motion = [&](double t) { return poseAtTime(s.truth, start + t); };
  for (SensorModel model : {SensorModel::Vlp16, SensorModel::Livox}) {
    SensorConfig config = sensorPreset(model);
    config.range_noise = 0.0;
    config.dropout = 0.0;
    const auto returns = sweepReturns(s.world, motion, period, config, 1, 37);
    ASSERT_GT(returns.size(), 2000u) << hba::toString(model);
    double worst = 0.0, still_worst = 0.0, last_time = 0.0;
    for (const Return& r : returns) {
      ASSERT_GE(r.time, last_time);  // fired in order
      ASSERT_LT(r.time, period);
      last_time = r.time;
      worst = std::max(worst, s.world.distanceToPrimitive(r.primitive, motion(r.time) * r.point));
      still_worst = std::max(still_worst, s.world.distanceToPrimitive(r.primitive, motion(0.0) * r.point));
    }
    EXPECT_LT(worst, 1e-6) << hba::toString(model);
    EXPECT_GT(still_worst, 0.05) << hba::toString(model);  // seen from the start's pose, the sweep is warped
    EXPECT_GT(last_time, 0.09);
  }
  // A spinning sensor fires a column's channels together.
  const SensorConfig vlp = sensorPreset(SensorModel::Vlp16);
  EXPECT_EQ(firingShare(vlp, 0), firingShare(vlp, 15));
  EXPECT_GT(firingShare(vlp, 16), firingShare(vlp, 15));
}

TEST(SimSensor, MeasuredRangeNoiseMatchesTheSetting) {
  const Simulation& s = test::smallSimulation();
  SensorConfig config = sensorPreset(SensorModel::Vlp16);
  config.range_noise = 0.05;
  config.dropout = 0.0;
  const auto returns = scanReturns(s.world, s.truth.poses[10], config, 5, 10);
  ASSERT_GT(returns.size(), 5000u);
  double sum = 0.0, sum_sq = 0.0;
  for (const Return& r : returns) {
    const double error = r.point.norm() - r.true_range;
    sum += error;
    sum_sq += error * error;
  }
  const double n = static_cast<double>(returns.size());
  const double mean = sum / n;
  const double sigma = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_NEAR(sigma, 0.05, 0.05 * 0.04);
  EXPECT_NEAR(mean, 0.0, 0.003);
}

TEST(SimSensor, DropoutRemovesTheConfiguredFraction) {
  const Simulation& s = test::smallSimulation();
  SensorConfig config = sensorPreset(SensorModel::Vlp16);
  config.range_noise = 0.0;
  config.dropout = 0.0;
  const double all = static_cast<double>(scanReturns(s.world, s.truth.poses[0], config, 1, 0).size());
  config.dropout = 0.3;
  const double kept = static_cast<double>(scanReturns(s.world, s.truth.poses[0], config, 1, 0).size());
  EXPECT_NEAR(kept / all, 0.7, 0.02);
}

TEST(SimSensor, RangesStayWithinTheSensorLimits) {
  const Simulation& s = test::smallSimulation();
  SensorConfig config = sensorPreset(SensorModel::Hdl32);
  config.max_range = 25.0;
  const auto returns = scanReturns(s.world, s.truth.poses[50], config, 2, 50);
  ASSERT_FALSE(returns.empty());
  for (const Return& r : returns) {
    EXPECT_LE(r.point.norm(), 25.0);
    EXPECT_GE(r.point.norm(), config.min_range);
    EXPECT_GE(r.intensity, 0.0f);
    EXPECT_LE(r.intensity, 255.0f);
  }
}

TEST(SimSensor, SameSeedAndFrameGiveTheSameScan) {
  const Simulation& s = test::smallSimulation();
  SensorConfig config = sensorPreset(SensorModel::Vlp16);
  const PointCloud a = scan(s.world, s.truth.poses[3], config, 9, 3);
  const PointCloud b = scan(s.world, s.truth.poses[3], config, 9, 3);
  const PointCloud other_frame = scan(s.world, s.truth.poses[3], config, 9, 4);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.intensity, b.intensity);
  EXPECT_NE(a.points, other_frame.points) << "each frame draws its own noise";
}

TEST(SimSensor, SpinningPresetsMatchTheirDataSheets) {
  struct Expected {
    SensorModel model;
    int channels;
    double lowest, highest;
  };
  for (const Expected& e :
       {Expected{SensorModel::Vlp16, 16, -15.0, 15.0}, Expected{SensorModel::Hdl32, 32, -30.67, 10.67},
        Expected{SensorModel::Hdl64, 64, -24.9, 2.0}, Expected{SensorModel::Os128, 128, -22.5, 22.5}}) {
    const SensorConfig config = sensorPreset(e.model);
    const auto directions = rayDirections(config, 0);
    ASSERT_EQ(directions.size(), config.raysPerFrame());
    ASSERT_EQ(config.channels, e.channels);
    double low = 90.0, high = -90.0;
    for (const Vec3& d : directions) {
      const double elevation = std::asin(d.z()) * 180.0 / M_PI;
      low = std::min(low, elevation);
      high = std::max(high, elevation);
      ASSERT_NEAR(d.norm(), 1.0, 1e-12);
    }
    EXPECT_NEAR(low, e.lowest, 1e-9) << hba::toString(e.model);
    EXPECT_NEAR(high, e.highest, 1e-9) << hba::toString(e.model);
  }
}

TEST(SimSensor, RosetteFillsItsConeAndNeverRepeats) {
  const SensorConfig config = sensorPreset(SensorModel::Livox);
  const auto first = rayDirections(config, 0);
  const auto second = rayDirections(config, 1);
  ASSERT_EQ(first.size(), 24000u);
  const double half_fov = 0.5 * config.field_of_view_deg * M_PI / 180.0;
  double widest = 0.0;
  int central = 0;
  for (const Vec3& d : first) {
    const double off_axis = std::acos(std::clamp(d.x(), -1.0, 1.0));
    ASSERT_LE(off_axis, half_fov + 1e-9);
    widest = std::max(widest, off_axis);
    if (off_axis < 0.25 * half_fov) ++central;
  }
  EXPECT_GT(widest, 0.98 * half_fov);
  EXPECT_GT(central, 100) << "the rosette also covers the centre";
  EXPECT_NE(first, second);
}

TEST(SimSensor, RejectsImpossibleSettings) {
  SensorConfig config = sensorPreset(SensorModel::Vlp16);
  config.range_noise = -0.1;
  EXPECT_THROW(validate(config), Error);
  config = sensorPreset(SensorModel::Vlp16);
  config.dropout = 1.0;
  EXPECT_THROW(validate(config), Error);
  config = sensorPreset(SensorModel::Vlp16);
  config.max_range = 0.1;
  EXPECT_THROW(validate(config), Error);
  EXPECT_FALSE(findEnum<SensorModel>("hdl128").has_value());
  EXPECT_EQ(findEnum<SensorModel>("os128"), SensorModel::Os128);
}

}  // namespace
}  // namespace hba::sim
