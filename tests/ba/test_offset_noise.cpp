// The settle check's yardstick: what fitting a window's frames to noise
// alone gains (offset_noise.hpp), and the window BA keeping its start when
// it gains no more than a multiple of it.
#include <gtest/gtest.h>

#include <cstdio>

#include "hba/ba/association.hpp"
#include "hba/ba/offset_noise.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/core/error.hpp"
#include "synthetic_window.hpp"

namespace hba::ba {
namespace {

// A frame's points on the plane z = 0 (in its own coordinates): a 2 x 2 m
// square at height `offset`, `count` points.
FrameCluster squareAt(std::uint32_t frame, double offset, int count) {
  PointCluster points;
  for (int i = 0; i < count; ++i) {
    const double u = -1.0 + 2.0 * (i % 10) / 9.0;
    const double v = -1.0 + 2.0 * ((i / 10) % 10) / 9.0;
    points.add(Vec3(u, v, offset));
  }
  return FrameCluster(frame, points);
}

TEST(FrameOffsets, SumTheFramesOffsetsAlongTheNormal) {
  // Three frames at identity see one plane at heights 0.01, -0.02 and 0.01
  // with 100, 100 and 200 points: mean 0.0025, offsets 0.0075, -0.0225,
  // 0.0075.
  PlaneObservation plane;
  plane.clusters = {squareAt(0, 0.01, 100), squareAt(1, -0.02, 100), squareAt(2, 0.01, 200)};
  const PlaneProblem problem({plane}, 3);
  const FrameOffsets offsets = frameOffsets(problem, std::vector<Pose>(3));
  const double expected = 100 * 0.0075 * 0.0075 + 100 * 0.0225 * 0.0225 + 200 * 0.0075 * 0.0075;
  EXPECT_NEAR(offsets.cost, expected, 1e-12);
  EXPECT_EQ(offsets.pairs, 3.0);
  EXPECT_EQ(offsets.planes, 1.0);

  // A pose moves a frame's offset: frame 1 lifted by 0.03 m meets the others.
  std::vector<Pose> poses(3);
  poses[1].t = Vec3(0.0, 0.0, 0.03);
  EXPECT_NEAR(frameOffsets(problem, poses).cost, 0.0, 1e-12);
}

TEST(FrameOffsets, NoiseGainIsOneVariancePerDegreeOfFreedom) {
  FrameOffsets offsets;
  offsets.cost = 2.0;
  offsets.pairs = 100.0;
  offsets.planes = 20.0;
  // 3 frames: 12 degrees of freedom, 100 - 20 - 12 = 68 left for the variance.
  EXPECT_NEAR(offsetNoiseGain(offsets, 3), 12.0 * 2.0 / 68.0, 1e-15);
  EXPECT_EQ(offsetNoiseGain(offsets, 1), 0.0);
  offsets.pairs = 30.0;  // fewer pairs than planes and poses can explain
  EXPECT_EQ(offsetNoiseGain(offsets, 3), 0.0);
}

// Started at the truth, a window of noisy planes can only fit the noise:
// on average it gains what offsetNoiseGain says (a yardstick that is off
// by a factor would make the settle check's threshold meaningless).
TEST(FrameOffsets, PredictWhatFittingTheNoiseGains) {
  double sum = 0.0;
  const int seeds = 20;
  for (int seed = 1; seed <= seeds; ++seed) {
    test::SyntheticWindowSpec spec;
    spec.noise_sigma = 0.02;
    spec.frames = 4;
    spec.seed = static_cast<std::uint32_t>(seed);
    const test::SyntheticWindow window = test::makeSyntheticWindow(spec);
    BaSettings settings = test::patchBaSettings();
    settings.motion_prior.enabled = false;
    settings.significant_gain = 0.0;
    const BaResult fit = optimizeWindow(window.scanPointers(), window.truth, settings);
    const PlaneProblem planes =
        associate(window.scanPointers(), window.truth, settings.planes, settings.reject_ratio).problem;
    const double gain = fit.fixed_map_cost_initial - fit.fixed_map_cost_final;
    const double noise = offsetNoiseGain(frameOffsets(planes, fit.poses), window.truth.size());
    ASSERT_GT(noise, 0.0);
    sum += gain / noise;
  }
  const double mean = sum / seeds;
  std::printf("fitting noise gains %.2f times offsetNoiseGain on average\n", mean);
  EXPECT_GT(mean, 0.6);
  EXPECT_LT(mean, 1.6);
}

// A window of 2 cm point noise whose start is off by `angle_deg` and
// `translation` per frame, and the BA settings of its 8 m patches.
test::SyntheticWindow noisyWindow(double angle_deg, double translation) {
  test::SyntheticWindowSpec spec;
  spec.noise_sigma = 0.02;
  spec.seed = 3;
  spec.perturb_angle_deg = angle_deg;
  spec.perturb_translation = translation;
  return test::makeSyntheticWindow(spec);
}

TEST(WindowBa, AWindowAtItsOptimumSettlesAndKeepsItsStart) {
  const test::SyntheticWindow window = noisyWindow(1.0, 0.2);
  BaSettings settings = test::patchBaSettings();
  const BaResult result = optimizeWindow(window.scanPointers(), window.truth, settings);
  EXPECT_TRUE(result.trusted);
  EXPECT_TRUE(result.settled);
  EXPECT_GT(result.gain_over_noise, 0.0);
  EXPECT_LT(result.gain_over_noise, settings.significant_gain);
  for (std::size_t i = 0; i < window.truth.size(); ++i) {
    EXPECT_EQ(result.poses[i].t, window.truth[i].t) << "frame " << i;
    EXPECT_EQ(result.poses[i].q.coeffs(), window.truth[i].q.coeffs()) << "frame " << i;
  }
  EXPECT_EQ(result.final_cost, result.last_association_initial_cost);
  // Off, the same window moves to the noise's optimum.
  settings.significant_gain = 0.0;
  const BaResult free = optimizeWindow(window.scanPointers(), window.truth, settings);
  EXPECT_FALSE(free.settled);
  EXPECT_NE(free.poses[1].t, window.truth[1].t);
}

TEST(WindowBa, AWindowWithSomethingToCorrectDoesNotSettle) {
  const test::SyntheticWindow window = noisyWindow(0.2, 0.03);
  const BaResult result = optimizeWindow(window.scanPointers(), window.initial, test::patchBaSettings());
  EXPECT_TRUE(result.trusted);
  EXPECT_FALSE(result.settled);
  EXPECT_GT(result.gain_over_noise, 100.0);
  const auto before = test::relativePoseError(window.initial, window.truth);
  const auto after = test::relativePoseError(result.poses, window.truth);
  EXPECT_LT(after.max_translation, before.max_translation / 3.0);
}

TEST(WindowBa, ANegativeSignificantGainIsRefused) {
  const test::SyntheticWindow window = test::makeSyntheticWindow(test::SyntheticWindowSpec{});
  BaSettings settings;
  settings.significant_gain = -1.0;
  EXPECT_THROW(optimizeWindow(window.scanPointers(), window.truth, settings), Error);
}

}  // namespace
}  // namespace hba::ba
