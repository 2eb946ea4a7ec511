#include <gtest/gtest.h>

#include "hba/voxel/downsample.hpp"

#include <cmath>
#include <map>
#include <random>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

TEST(VoxelKey, CellIsFloorForEverySignIntegersAndLimits) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.0,
                                0.5,
                                -0.5,
                                1e-300,
                                -1e-300,
                                std::nextafter(-1.0, 0.0),
                                std::nextafter(1.0, 0.0),
                                -4503599627370495.5,
                                4503599627370495.5,
                                3.0e18,
                                -3.0e18};
  for (int i = 0; i < 100000; ++i) values.push_back(u(rng));
  for (int i = -50; i <= 50; ++i) values.push_back(i);
  for (double v : values) {
    EXPECT_EQ(VoxelKey::cell(v), static_cast<std::int64_t>(std::floor(v))) << v;
  }
  // Beyond int64 and NaN: an edge cell, never an overflowing conversion.
  EXPECT_EQ(VoxelKey::cell(1e30), VoxelKey::cell(5e18));
  EXPECT_EQ(VoxelKey::cell(-1e30), VoxelKey::cell(-5e18));
  EXPECT_EQ(VoxelKey::cell(std::nan("")), VoxelKey::cell(-1e30));
}

TEST(Downsample, KeepsOneCentroidPerVoxelInFirstSeenOrder) {
  PointCloud cloud;
  cloud.add(Vec3f(1.2f, 0.1f, 0.1f), 10.f);  // voxel (1,0,0)
  cloud.add(Vec3f(0.1f, 0.1f, 0.1f), 2.f);   // voxel (0,0,0)
  cloud.add(Vec3f(0.3f, 0.5f, 0.7f), 4.f);   // voxel (0,0,0)
  cloud.add(Vec3f(1.6f, 0.3f, 0.9f), 20.f);  // voxel (1,0,0)
  cloud.add(Vec3f(-0.1f, 0.1f, 0.1f), 7.f);  // voxel (-1,0,0): floor, not truncation
  const PointCloud out = downsample(cloud, 1.0);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_TRUE(out.hasIntensity());
  EXPECT_TRUE(out.points[0].isApprox(Vec3f(1.4f, 0.2f, 0.5f)));
  EXPECT_FLOAT_EQ(out.intensity[0], 15.f);
  EXPECT_TRUE(out.points[1].isApprox(Vec3f(0.2f, 0.3f, 0.4f)));
  EXPECT_FLOAT_EQ(out.intensity[1], 3.f);
  EXPECT_TRUE(out.points[2].isApprox(Vec3f(-0.1f, 0.1f, 0.1f)));
}

TEST(Downsample, WithoutIntensityAndDegenerateSizes) {
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.add(Vec3f(0.01f * i, 0.f, 0.f));
  const PointCloud out = downsample(cloud, 0.25);
  EXPECT_EQ(out.size(), 4u);
  EXPECT_FALSE(out.hasIntensity());
  EXPECT_EQ(downsample(cloud, 0.0).size(), 100u);   // disabled
  EXPECT_EQ(downsample(cloud, -1.0).size(), 100u);  // disabled
  EXPECT_TRUE(downsample(PointCloud{}, 0.1).empty());
}

TEST(Downsample, ResultDoesNotExceedOnePointPerVoxel) {
  PointCloud cloud;
  for (int x = 0; x < 20; ++x) {
    for (int y = 0; y < 20; ++y) cloud.add(Vec3f(0.05f * x + 0.001f, 0.05f * y + 0.001f, 0.f));
  }
  const PointCloud out = downsample(cloud, 0.1);  // 2x2 input points per cell
  EXPECT_EQ(out.size(), 100u);
}

// The rule spelled out the slow way: cells keyed in an ordered map, numbered
// when first hit, centroids summed in input order.
PointCloud referenceDownsample(const PointCloud& cloud, double size) {
  std::map<VoxelKey, std::size_t> cell_of;
  std::vector<Vec3> sums;
  std::vector<double> intensities;
  std::vector<double> counts;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const VoxelKey key = VoxelKey::of(cloud.points[i].cast<double>(), size);
    const auto [it, added] = cell_of.emplace(key, sums.size());
    if (added) {
      sums.push_back(Vec3::Zero());
      intensities.push_back(0.0);
      counts.push_back(0.0);
    }
    sums[it->second] += cloud.points[i].cast<double>();
    intensities[it->second] += cloud.intensity[i];
    counts[it->second] += 1.0;
  }
  PointCloud out;
  for (std::size_t c = 0; c < sums.size(); ++c) {
    out.add((sums[c] * (1.0 / counts[c])).cast<float>(),
            static_cast<float>(intensities[c] * (1.0 / counts[c])));
  }
  return out;
}

// Random points around `centre` within +-`extent` m, some cells shared.
PointCloud randomCloud(const Vec3& centre, double extent, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.add((centre + Vec3(u(rng), u(rng), 0.01 * u(rng))).cast<float>(), static_cast<float>(i % 97));
  }
  return cloud;
}

void expectIdentical(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.points[i], b.points[i]) << "point " << i;
    ASSERT_EQ(a.intensity[i], b.intensity[i]) << "point " << i;
  }
}

// Scan-sized clouds take the packed-key path, UTM-like offsets included.
TEST(Downsample, MatchesTheReferenceRuleNearAndFarFromTheOrigin) {
  for (const Vec3& centre : {Vec3(0, 0, 0), Vec3(512345.0, 5412345.0, 230.0)}) {
    const PointCloud cloud = randomCloud(centre, 20.0, 20000, 7);
    expectIdentical(downsample(cloud, 0.5), referenceDownsample(cloud, 0.5));
  }
}

// The expected points a cell only size the voxel table: a table far too
// small (grown many times over) or far too large gives the same cloud.
TEST(Downsample, TheTableSizeHintNeverChangesTheResult) {
  const PointCloud cloud = randomCloud(Vec3(100.0, -40.0, 3.0), 20.0, 50000, 11);
  const PointCloud reference = referenceDownsample(cloud, 0.3);
  ASSERT_LT(reference.size(), cloud.size());  // cells are shared
  for (const std::size_t hint : {std::size_t{0}, std::size_t{1}, std::size_t{4}, std::size_t{1000000}}) {
    expectIdentical(downsample(cloud, 0.3, hint), reference);
  }
}

// More than 2^21 cells along an axis: full keys, same rule.
TEST(Downsample, MatchesTheReferenceRuleOverAHugeSpan) {
  PointCloud cloud = randomCloud(Vec3::Zero(), 5.0, 5000, 3);
  const PointCloud far = randomCloud(Vec3(4.0e5, 0, 0), 5.0, 5000, 4);
  for (std::size_t i = 0; i < far.size(); ++i) cloud.add(far.points[i], far.intensity[i]);
  expectIdentical(downsample(cloud, 0.1), referenceDownsample(cloud, 0.1));
}

// Non-finite points cannot be packed; they still land in (edge) cells
// instead of corrupting the others.
TEST(Downsample, NonFinitePointsDoNotDisturbTheFiniteCells) {
  PointCloud cloud = randomCloud(Vec3::Zero(), 3.0, 2000, 5);
  cloud.add(Vec3f(std::nanf(""), 0.f, 0.f), 1.f);
  cloud.add(Vec3f(INFINITY, 1.f, 1.f), 1.f);
  const PointCloud out = downsample(cloud, 0.2);
  const PointCloud reference = referenceDownsample(cloud, 0.2);
  ASSERT_EQ(out.size(), reference.size());
  for (std::size_t i = 0; i + 2 < out.size(); ++i) EXPECT_EQ(out.points[i], reference.points[i]);
}

}  // namespace
}  // namespace hba::voxel
