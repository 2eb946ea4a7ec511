// The drift model: errors grow with distance at the configured rates; the
// loop-closed variant stays bounded.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/sim/drift.hpp"

namespace hba::sim {
namespace {

// A straight drive along x, 0.5 m per frame.
std::vector<Pose> straightDrive(std::size_t frames) {
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < frames; ++k) {
    poses.emplace_back(Quat::Identity(), Vec3(0.5 * static_cast<double>(k), 0.0, 1.8));
  }
  return poses;
}

DriftConfig only(double translation, double rotation_deg_per_m, double vertical) {
  DriftConfig c;
  c.translation = translation;
  c.rotation_deg_per_m = rotation_deg_per_m;
  c.vertical = vertical;
  return c;
}

TEST(SimDrift, TranslationErrorGrowsAtTheConfiguredRate) {
  const auto truth = straightDrive(401);  // 200 m
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto drifted = applyDrift(truth, only(0.01, 0.0, 0.0), seed);
    EXPECT_EQ(drifted[0].t, truth[0].t);
    for (std::size_t k : {40u, 100u, 200u}) {  // 20, 50, 100 m
      const double distance = 0.5 * static_cast<double>(k);
      const double error = (drifted[k].t - truth[k].t).norm();
      // The bias direction wanders slowly, so the error is at most rate x
      // distance and close to it over distances short against 300 m.
      EXPECT_LE(error, 0.01 * distance + 1e-9) << "seed " << seed << " at " << distance << " m";
      EXPECT_GE(error, 0.8 * 0.01 * distance) << "seed " << seed << " at " << distance << " m";
    }
  }
}

TEST(SimDrift, HeadingErrorGrowsAtTheConfiguredRate) {
  const auto truth = straightDrive(401);
  const double rate = 0.02;  // deg per metre
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto drifted = applyDrift(truth, only(0.0, rate, 0.0), seed);
    for (std::size_t k : {40u, 100u, 200u}) {
      const double distance = 0.5 * static_cast<double>(k);
      const Vec3 rotation_error = so3Log(Mat3(truth[k].R().transpose() * drifted[k].R()));
      const double degrees = rotation_error.norm() * 180.0 / M_PI;
      EXPECT_LE(degrees, rate * distance * 1.01) << "seed " << seed;  // + the tenth in tilt
      EXPECT_GE(degrees, 0.7 * rate * distance) << "seed " << seed;
      // Mostly a heading (yaw) error, as in real odometry.
      EXPECT_GT(std::abs(rotation_error.z()), 0.9 * rotation_error.norm());
    }
    // A heading error bends the path: lateral error grows faster than linearly.
    EXPECT_GT(std::abs(drifted[400].t.y() - truth[400].t.y()),
              2.5 * std::abs(drifted[200].t.y() - truth[200].t.y()));
  }
}

TEST(SimDrift, HeightDriftsLinearlyWithDistance) {
  const auto truth = straightDrive(201);
  const auto drifted = applyDrift(truth, only(0.0, 0.0, 0.003), 2);
  for (std::size_t k : {20u, 100u, 200u}) {
    EXPECT_NEAR(std::abs(drifted[k].t.z() - truth[k].t.z()), 0.003 * 0.5 * k, 1e-9);
    EXPECT_NEAR(drifted[k].t.head<2>().x(), truth[k].t.x(), 1e-9);
  }
}

TEST(SimDrift, LoopClosedNoiseIsSmallAndDoesNotGrow) {
  const auto truth = straightDrive(2001);
  DriftConfig c;
  c.loop_closed = true;
  const auto noisy = applyDrift(truth, c, 4);
  double early = 0.0, late = 0.0;
  for (std::size_t k = 1; k <= 1000; ++k) early += (noisy[k].t - truth[k].t).squaredNorm();
  for (std::size_t k = 1001; k <= 2000; ++k) late += (noisy[k].t - truth[k].t).squaredNorm();
  const double sigma_early = std::sqrt(early / 3000.0), sigma_late = std::sqrt(late / 3000.0);
  EXPECT_NEAR(sigma_early, c.closed_translation_sigma, 0.1 * c.closed_translation_sigma);
  EXPECT_NEAR(sigma_late, c.closed_translation_sigma, 0.1 * c.closed_translation_sigma);
}

TEST(SimDrift, SameSeedSamePoses) {
  const auto truth = straightDrive(100);
  const auto a = applyDrift(truth, DriftConfig{}, 8);
  const auto b = applyDrift(truth, DriftConfig{}, 8);
  const auto c = applyDrift(truth, DriftConfig{}, 9);
  EXPECT_EQ(a.back().t, b.back().t);
  EXPECT_NE(a.back().t, c.back().t);
}

TEST(SimDrift, RejectsNegativeRates) {
  EXPECT_THROW(applyDrift(straightDrive(3), only(-0.01, 0.0, 0.0), 1), Error);
  EXPECT_THROW(applyDrift(straightDrive(3), only(0.0, 0.0, 2.0), 1), Error);
}

// Jitter: per-frame, independent errors of the configured size on top of
// the drift; without jitter the drift's own bytes are unchanged.
TEST(SimDrift, JitterAddsIndependentPerFrameNoiseOfTheConfiguredSize) {
  const auto truth = straightDrive(2001);
  DriftConfig smooth = only(0.01, 0.01, 0.0);
  DriftConfig jittery = smooth;
  jittery.jitter_translation = 0.03;
  jittery.jitter_rotation_deg = 0.2;
  const auto a = applyDrift(truth, smooth, 7);
  const auto b = applyDrift(truth, jittery, 7);
  EXPECT_EQ(a[0].t, b[0].t);  // the first pose fixes the frame
  double sum_t = 0.0, sum_r = 0.0, lag = 0.0;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Vec3 dt = b[k].t - a[k].t;
    sum_t += dt.squaredNorm();
    sum_r += so3Log(Quat(a[k].q.conjugate() * b[k].q)).squaredNorm();
    if (k > 1) lag += dt.dot(b[k - 1].t - a[k - 1].t);
  }
  const double n = static_cast<double>(truth.size() - 1);
  EXPECT_NEAR(std::sqrt(sum_t / (3 * n)), 0.03, 0.002);
  EXPECT_NEAR(std::sqrt(sum_r / (3 * n)) * 180.0 / M_PI, 0.2, 0.015);
  EXPECT_LT(std::abs(lag / n), 0.1 * sum_t / n);  // independent from frame to frame
  const auto again = applyDrift(truth, smooth, 7);
  for (std::size_t k = 0; k < truth.size(); ++k) EXPECT_EQ(again[k].t, a[k].t);
  jittery.jitter_translation = -1.0;
  EXPECT_THROW(applyDrift(truth, jittery, 7), Error);
}

}  // namespace
}  // namespace hba::sim
