#include <gtest/gtest.h>

#include "hba/voxel/downsample.hpp"

namespace hba::voxel {
namespace {

TEST(Downsample, KeepsOneCentroidPerVoxelInFirstSeenOrder) {
  PointCloud cloud;
  cloud.add(Vec3f(1.2f, 0.1f, 0.1f), 10.f);   // voxel (1,0,0)
  cloud.add(Vec3f(0.1f, 0.1f, 0.1f), 2.f);    // voxel (0,0,0)
  cloud.add(Vec3f(0.3f, 0.5f, 0.7f), 4.f);    // voxel (0,0,0)
  cloud.add(Vec3f(1.6f, 0.3f, 0.9f), 20.f);   // voxel (1,0,0)
  cloud.add(Vec3f(-0.1f, 0.1f, 0.1f), 7.f);   // voxel (-1,0,0): floor, not truncation
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

}  // namespace
}  // namespace hba::voxel
