// Streaming voxel merge of posed scans.
#include <gtest/gtest.h>

#include <vector>

#include "hba/core/error.hpp"
#include "hba/eval/map_entropy.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/io/scan_source.hpp"
#include "synthetic_scans.hpp"

namespace hba::eval {
namespace {

// Two scans whose points land in the same 1 m voxel once posed.
struct TwoScans {
  PointCloud a, b;
  Pose pose_a, pose_b{Quat::Identity(), Vec3(0.5, 0, 0)};
  TwoScans() {
    a.add(Vec3f(0.1f, 0.1f, 0.1f), 10.0f);
    b.add(Vec3f(-0.2f, 0.3f, 0.5f), 30.0f);  // world (0.3, 0.3, 0.5)
    b.add(Vec3f(2.0f, 0.0f, 0.0f), 50.0f);   // world (2.5, 0, 0): its own voxel
  }
  PointCloud merge(const MapSettings& settings) const {
    VoxelMerger merger(settings);
    merger.add(a, pose_a, 0);
    merger.add(b, pose_b, 1);
    return merger.result();
  }
};

TEST(MergedMap, CentroidRuleAveragesPositionAndIntensity) {
  MapSettings s;
  s.voxel = 1.0;
  const PointCloud map = TwoScans().merge(s);
  ASSERT_EQ(map.size(), 2u);
  EXPECT_TRUE(map.points[0].isApprox(Vec3f(0.2f, 0.2f, 0.3f)));
  EXPECT_FLOAT_EQ(map.intensity[0], 20.0f);
  EXPECT_TRUE(map.points[1].isApprox(Vec3f(2.5f, 0.0f, 0.0f)));
}

TEST(MergedMap, FirstPointRuleAndColourChannels) {
  MapSettings s;
  s.voxel = 1.0;
  s.rule = VoxelRule::FirstPoint;
  s.color = MapColor::Scan;
  PointCloud map = TwoScans().merge(s);
  EXPECT_TRUE(map.points[0].isApprox(Vec3f(0.1f, 0.1f, 0.1f)));
  EXPECT_EQ(map.intensity, (std::vector<float>{0.0f, 1.0f}));  // first scan per voxel
  s.color = MapColor::Height;
  map = TwoScans().merge(s);
  EXPECT_FLOAT_EQ(map.intensity[0], 0.1f);
}

TEST(MergedMap, NonPositiveVoxelKeepsEveryPoint) {
  MapSettings s;
  s.voxel = 0.0;
  EXPECT_EQ(TwoScans().merge(s).size(), 3u);
}

TEST(MergedMap, DownsampleMapOfAWorldCloud) {
  PointCloud cloud;  // no intensity: none in the output either
  for (int i = 0; i < 100; ++i) cloud.add(Vec3f(0.01f * i, 0, 0));
  MapSettings s;
  s.voxel = 0.25;
  const PointCloud map = downsampleMap(cloud, s);
  EXPECT_EQ(map.size(), 4u);
  EXPECT_FALSE(map.hasIntensity());
  EXPECT_THROW(parseEnum<MapColor>("rainbow"), Error);
}

// Scans that are no folder on disk: merged as a merger fed them one by one.
TEST(MergedMap, ScansInMemoryAreMergedWithTheirPoses) {
  const std::vector<Pose> poses = test::syntheticPoses();
  const std::vector<PointCloud> scans = test::syntheticScans(poses);
  const io::MemoryScanSource source(scans);
  MapSettings s;
  s.voxel = 0.1;
  s.color = MapColor::Scan;
  const PointCloud map = buildMergedMap(source, poses, s);
  VoxelMerger merger(s);
  for (std::size_t i = 0; i < scans.size(); ++i)
    merger.add(scans[i], poses[i], static_cast<std::uint32_t>(i));
  const PointCloud expected = merger.result();
  ASSERT_GT(map.size(), 1000u);
  EXPECT_EQ(map.points, expected.points);
  EXPECT_EQ(map.intensity, expected.intensity);
  EXPECT_THROW(buildMergedMap(source, {poses.front()}, s), Error);
}

TEST(MapEntropy, WrongPosesBlurAMapOfScansInMemory) {
  const std::vector<Pose> poses = test::syntheticPoses();
  const io::MemoryScanSource source(test::syntheticScans(poses));
  std::vector<Pose> wrong = poses;
  wrong[2].t.x() += 0.15;  // a doubled wall
  MmeSettings entropy;
  entropy.radius = 0.2;
  const MmeResult good = meanMapEntropy(buildMergedMap(source, poses, MapSettings{}), entropy);
  const MmeResult bad = meanMapEntropy(buildMergedMap(source, wrong, MapSettings{}), entropy);
  ASSERT_GT(good.used, 100u);
  EXPECT_GT(bad.mme, good.mme + 0.2);
}

}  // namespace
}  // namespace hba::eval
