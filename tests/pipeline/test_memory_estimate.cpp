#include "hba/pipeline/memory_estimate.hpp"

#include <gtest/gtest.h>

#include "hba/pipeline/window_size.hpp"

#include <algorithm>

#include "hba/io/scan_source.hpp"
#include "hba/pyramid/window_plan.hpp"

namespace hba::pipeline {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

const StageMemory* stageOf(const MemoryEstimate& estimate, Stage stage) {
  const auto found = std::find_if(estimate.stages.begin(), estimate.stages.end(),
                                  [&](const StageMemory& s) { return s.stage == stage; });
  return found == estimate.stages.end() ? nullptr : &*found;
}

// `settings` with the window a run of `density` plans (plan.hpp).
HbaSettings sized(const HbaSettings& settings, const ScanDensity& density) {
  return withWindowSize(settings, chooseWindowSize(settings, density.points));
}

HbaSettings oneLayer() {
  HbaSettings settings;
  settings.layers = 1;
  return settings;
}

// Its dense system is (6K)^2 doubles a copy: twice the frames, four times
// the memory, and the issue's 4717 scans need far more than 24 GB.
TEST(MemoryEstimate, TheGlobalBaGrowsWithTheSquareOfItsFrames) {
  const ScanDensity none;  // no points: the dense part alone
  const double base = estimateMemory(2, none, sized(oneLayer(), none)).peakBytes();
  const double k1000 = estimateMemory(1000, none, sized(oneLayer(), none)).peakBytes() - base;
  const double k2000 = estimateMemory(2000, none, sized(oneLayer(), none)).peakBytes() - base;
  EXPECT_NEAR(k2000 / k1000, 4.0, 0.01);
  ScanDensity livox;
  livox.points = 4000;
  livox.refine_points = 2000;
  const MemoryEstimate issue = estimateMemory(4717, livox, sized(oneLayer(), livox));
  EXPECT_EQ(issue.largest().stage, Stage::GlobalBa);
  EXPECT_EQ(issue.top_frames, 4717u);
  EXPECT_GT(issue.peakBytes(), 40 * kGiB);
  EXPECT_NE(issue.largest().detail.find("a dense 28302 x 28302 system and 18.9 M points"), std::string::npos)
      << issue.largest().detail;
  // The default pyramid over the same scans: its top layer is small.
  HbaSettings defaults;
  const MemoryEstimate pyramid = estimateMemory(4717, livox, sized(defaults, livox));
  EXPECT_GT(pyramid.layers, 1);
  EXPECT_LT(pyramid.peakBytes(), 2 * kGiB);
}

TEST(MemoryEstimate, TheLayersAreTheRunsOwn) {
  HbaSettings settings;
  settings.window = 10;  // the paper's windows and the default rule: 314 frames -> 62 -> 12 (hku1)
  const MemoryEstimate estimate = estimateMemory(314, ScanDensity{}, sized(settings, ScanDensity{}));
  // The default stride (half the window) resolved, as the run resolves it.
  EXPECT_EQ(estimate.layers,
            pyramid::layerCount(314, withWindowSize(settings, chooseWindowSize(settings, 0.0))));
  EXPECT_EQ(estimate.layers, 3);
  EXPECT_EQ(estimate.top_frames, 12u);
  settings.layers = 99;  // more than the sequence holds
  EXPECT_EQ(estimateMemory(314, ScanDensity{}, sized(settings, ScanDensity{})).layers,
            pyramid::maxLayerCount(314, 10, 5));
  // An automatic window is the plan's to work out (plan.hpp), not the estimate's.
  EXPECT_THROW(estimateMemory(314, ScanDensity{}, HbaSettings()), Error);
}

// A block holds refine_max_points at most; beyond one block, the rigid
// groups follow (with one layer there is only the self-check).
TEST(MemoryEstimate, TheRefinementHoldsOneBlockAtMost) {
  ScanDensity density;
  density.points = 1e5;
  density.refine_points = 1e5;
  HbaSettings settings;
  const MemoryEstimate small = estimateMemory(100, density, sized(settings, density));
  const MemoryEstimate large = estimateMemory(1000, density, sized(settings, density));
  ASSERT_TRUE(stageOf(small, Stage::Refinement));
  ASSERT_TRUE(stageOf(large, Stage::Refinement));
  EXPECT_FALSE(stageOf(small, Stage::RefinementGroups));
  EXPECT_TRUE(stageOf(large, Stage::RefinementGroups));
  // 1000 frames hold as much at once as 200 (20 M points, one whole block).
  EXPECT_DOUBLE_EQ(stageOf(large, Stage::Refinement)->bytes,
                   stageOf(estimateMemory(200, density, sized(settings, density)), Stage::Refinement)->bytes);
  EXPECT_LT(stageOf(small, Stage::Refinement)->bytes, stageOf(large, Stage::Refinement)->bytes);
  EXPECT_TRUE(stageOf(estimateMemory(1000, density, sized(oneLayer(), density)), Stage::SelfCheck));
}

std::vector<PointCloud> gridScans(const std::vector<int>& sides) {
  std::vector<PointCloud> scans;
  for (int side : sides) {
    PointCloud scan;
    for (int x = 0; x < side; ++x) {
      for (int y = 0; y < side; ++y) scan.add(Vec3f(0.5f * x, 0.5f * y, 0.0f));
    }
    scans.push_back(scan);
  }
  return scans;
}

// Downsampled as the run does it, and the unsampled scans counted by their
// sizes: 0.5 m grids keep every point at 0.1 m, a quarter at 1 m.
TEST(MemoryEstimate, TheDensityIsSampledAsTheRunDownsamples) {
  const io::MemoryScanSource scans(gridScans({10, 20, 30, 40, 50}));  // 100 ... 2500 points
  HbaSettings settings;
  settings.scan_voxel = 0.1;
  settings.refine_scan_voxel = 1.0;
  const ScanDensity all = sampleScanDensity(scans, settings, 5);
  EXPECT_EQ(all.sampled, 5u);
  EXPECT_DOUBLE_EQ(all.points, (100 + 400 + 900 + 1600 + 2500) / 5.0);
  EXPECT_DOUBLE_EQ(all.refine_points, (25 + 100 + 225 + 400 + 625) / 5.0);
  // Two scans read (the first and last), the others by their sizes.
  const ScanDensity two = sampleScanDensity(scans, settings, 2);
  EXPECT_EQ(two.sampled, 2u);
  EXPECT_DOUBLE_EQ(two.points, all.points);
}

}  // namespace
}  // namespace hba::pipeline
