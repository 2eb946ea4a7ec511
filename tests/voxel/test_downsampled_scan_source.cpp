// Downsampling as a source wrapping another: each scan exactly as
// voxel::downsample gives it, any source, no voxel = the scans untouched.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/voxel/downsample.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"

namespace hba::voxel {
namespace {

std::vector<PointCloud> randomScans() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-5.0f, 5.0f);
  std::vector<PointCloud> scans(3);
  for (PointCloud& scan : scans) {
    for (int k = 0; k < 2000; ++k)
      scan.add(Vec3f(coordinate(rng), coordinate(rng), coordinate(rng)), coordinate(rng));
  }
  return scans;
}

void expectSame(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a.points[k], b.points[k]) << "point " << k;
  EXPECT_EQ(a.intensity, b.intensity);
}

TEST(DownsampledScanSource, EachScanAsDownsampleGivesIt) {
  const std::vector<PointCloud> scans = randomScans();
  const io::MemoryScanSource memory(scans);
  const DownsampledScanSource source(memory, 0.5);
  ASSERT_EQ(source.size(), scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const PointCloud loaded = source.load(i);
    EXPECT_LT(loaded.size(), scans[i].size());
    expectSame(downsample(scans[i], 0.5), loaded);
  }
}

TEST(DownsampledScanSource, NoVoxelKeepsEveryPointAndSourcesStack) {
  const std::vector<PointCloud> scans = randomScans();
  const io::MemoryScanSource memory(scans);
  expectSame(scans[1], DownsampledScanSource(memory, 0.0).load(1));
  // Stacked: each wrapper downsamples what the one inside gives.
  const DownsampledScanSource fine(memory, 0.25);
  const DownsampledScanSource coarse(fine, 1.0);
  EXPECT_LT(coarse.load(0).size(), fine.load(0).size());
  expectSame(downsample(downsample(scans[0], 0.25), 1.0), coarse.load(0));
}

TEST(DownsampledScanSource, PassesOnTheErrorsOfItsSource) {
  const io::MemoryScanSource memory(randomScans());
  EXPECT_THROW(DownsampledScanSource(memory, 0.5).load(3), Error);
}

}  // namespace
}  // namespace hba::voxel
