#include <gtest/gtest.h>

#include <random>

#include <tbb/global_control.h>

#include "hba/core/error.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::voxel {
namespace {

// `count` points on the square [lo, hi]^2 of the plane `axis` = `offset`.
void addSquare(PointCloud& cloud, std::mt19937& rng, int axis, float offset, float lo, float hi, int count) {
  std::uniform_real_distribution<float> u(lo, hi);
  for (int k = 0; k < count; ++k) {
    Vec3f p(u(rng), u(rng), u(rng));
    p(axis) = offset;
    cloud.add(p);
  }
}

std::vector<const PointCloud*> pointers(const std::vector<PointCloud>& scans) {
  std::vector<const PointCloud*> out;
  for (const auto& s : scans) out.push_back(&s);
  return out;
}

TEST(PlaneMap, FindsAPlaneSeenByTwoFrames) {
  std::mt19937 rng(1);
  std::vector<PointCloud> scans(2);
  for (auto& s : scans) addSquare(s, rng, 2, 1.0f, 0.2f, 3.8f, 200);
  PlaneSettings settings;
  const auto planes = extractPlanes(pointers(scans), {Pose(), Pose()}, settings);
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_EQ(planes[0].depth, 0);
  EXPECT_EQ(planes[0].points.size(), 400u);
  EXPECT_EQ(planes[0].points.front().frame, 0u);
  EXPECT_EQ(planes[0].points.back().frame, 1u);
  EXPECT_EQ(planes[0].points.back().index, 199u);
}

TEST(PlaneMap, PosesPlaceTheScansInTheWorld) {
  // Frame 1 sees the same wall from 1 m further: only with its pose do the
  // two scans share one plane.
  std::mt19937 rng(2);
  std::vector<PointCloud> scans(2);
  addSquare(scans[0], rng, 2, 1.0f, 0.2f, 3.8f, 200);
  addSquare(scans[1], rng, 2, 0.0f, 0.2f, 3.8f, 200);
  const Pose shifted(Quat::Identity(), Vec3(0, 0, 1));
  EXPECT_EQ(extractPlanes(pointers(scans), {Pose(), shifted}, PlaneSettings{}).size(), 1u);
  EXPECT_TRUE(extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{}).empty());
}

TEST(PlaneMap, PlaneSeenByOneFrameIsDropped) {
  std::mt19937 rng(3);
  std::vector<PointCloud> scans(2);
  addSquare(scans[0], rng, 2, 1.0f, 0.2f, 3.8f, 200);
  addSquare(scans[1], rng, 0, 9.0f, 8.2f, 11.8f, 200);  // elsewhere
  EXPECT_TRUE(extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{}).empty());
  PlaneSettings single;
  single.min_frames = 1;
  EXPECT_EQ(extractPlanes(pointers(scans), {Pose(), Pose()}, single).size(), 2u);
}

TEST(PlaneMap, SplitsACornerIntoSingleWallPlanes) {
  // A floor z = 1 and a wall x = 1.5 inside one 4 m voxel: the root fails the
  // test, octants pass; no plane may mix floor and wall points.
  std::mt19937 rng(4);
  std::vector<PointCloud> scans(2);
  for (auto& s : scans) {
    addSquare(s, rng, 2, 1.0f, 0.05f, 3.95f, 1500);
    addSquare(s, rng, 0, 1.5f, 0.05f, 3.95f, 1500);
  }
  const auto planes = extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{});
  ASSERT_GE(planes.size(), 4u);
  std::size_t covered = 0;
  for (const auto& plane : planes) {
    EXPECT_GE(plane.depth, 1);
    int floor = 0, wall = 0;
    for (const PointRef& r : plane.points) {
      const Vec3f& p = scans[r.frame].points[r.index];
      (p.z() == 1.0f && p.x() != 1.5f ? floor : wall) += 1;
    }
    EXPECT_TRUE(floor == 0 || wall == 0) << floor << " floor, " << wall << " wall points";
    covered += plane.points.size();
  }
  EXPECT_GT(covered, 3000u);  // most points end up in planes
}

TEST(PlaneMap, RejectsLinesAndScatter) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.1f, 3.9f);
  std::vector<PointCloud> line(2), blob(2);
  for (int f = 0; f < 2; ++f) {
    for (int k = 0; k < 100; ++k) {
      line[f].add(Vec3f(u(rng), 2.0f + 0.001f * u(rng), 2.0f + 0.001f * u(rng)));
      blob[f].add(Vec3f(u(rng), u(rng), u(rng)));
    }
  }
  EXPECT_TRUE(extractPlanes(pointers(line), {Pose(), Pose()}, PlaneSettings{}).empty());
  EXPECT_TRUE(extractPlanes(pointers(blob), {Pose(), Pose()}, PlaneSettings{}).empty());
}

TEST(PlaneMap, OutputIsIdenticalForAnyThreadCount) {
  std::mt19937 rng(6);
  std::vector<PointCloud> scans(3);
  for (auto& s : scans) {
    for (int wall = 0; wall < 6; ++wall) {
      addSquare(s, rng, wall % 3, 1.0f + 4.0f * wall, -10.f, 20.f, 800);
    }
  }
  const std::vector<Pose> poses(3, Pose());
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return extractPlanes(pointers(scans), poses, PlaneSettings{});
  };
  const auto one = run(1);
  const auto two = run(2);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_FALSE(one.empty());
  for (std::size_t p = 0; p < one.size(); ++p) {
    ASSERT_EQ(one[p].points.size(), two[p].points.size());
    for (std::size_t k = 0; k < one[p].points.size(); ++k) {
      EXPECT_EQ(one[p].points[k].frame, two[p].points[k].frame);
      EXPECT_EQ(one[p].points[k].index, two[p].points[k].index);
    }
  }
}

void expectSameFeatures(const std::vector<PlaneFeature>& a, const std::vector<PlaneFeature>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    EXPECT_EQ(a[p].depth, b[p].depth);
    ASSERT_EQ(a[p].points.size(), b[p].points.size());
    for (std::size_t k = 0; k < a[p].points.size(); ++k) {
      EXPECT_EQ(a[p].points[k].frame, b[p].points[k].frame);
      EXPECT_EQ(a[p].points[k].index, b[p].points[k].index);
    }
  }
}

TEST(PlaneMap, TwoVoxelsAtOnceGiveEachExtractionsPlanes) {
  std::mt19937 rng(8);
  std::vector<PointCloud> scans(4);
  for (auto& s : scans) {
    for (int wall = 0; wall < 6; ++wall) addSquare(s, rng, wall % 3, 1.3f + 3.7f * wall, -9.f, 9.f, 3000);
  }
  std::vector<Pose> poses;
  for (int f = 0; f < 4; ++f) {
    // Far from the origin, turned off the axes, each frame a little apart.
    poses.emplace_back(Quat(Eigen::AngleAxisd(0.3 + 0.001 * f, Vec3(0.3, 0.2, 1.0).normalized())),
                       Vec3(0.01 * f - 350.0, 0.005 * f + 1200.0, -0.002 * f));
  }
  PlaneSettings coarse;
  coarse.voxel_size = 4.0;
  for (const double fine_voxel : {4.0, 2.0, 1.0, 1.5}) {  // 1.5: cells that do not nest
    PlaneSettings fine = coarse;
    fine.voxel_size = fine_voxel;
    const auto [both_coarse, both_fine] =
        extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, fine_voxel);
    ASSERT_FALSE(both_fine.empty()) << fine_voxel;
    expectSameFeatures(both_coarse, extractPlanes(pointers(scans), poses, coarse));
    expectSameFeatures(both_fine, extractPlanes(pointers(scans), poses, fine));
  }
  EXPECT_THROW(extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, 8.0), Error);
  EXPECT_THROW(extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, 0.0), Error);
}

TEST(PlaneMap, PlaneTestUsesEigenvalueRatios) {
  PlaneSettings s;  // theta 0.05, line ratio 0.25
  EXPECT_TRUE(passesPlaneTest(Vec3(0.01, 1.0, 1.0), s));
  EXPECT_FALSE(passesPlaneTest(Vec3(0.06, 1.0, 1.0), s));   // too thick
  EXPECT_FALSE(passesPlaneTest(Vec3(0.01, 0.02, 1.0), s));  // a line
  EXPECT_FALSE(passesPlaneTest(Vec3(0.0, 0.0, 0.0), s));    // one point
}

TEST(PlaneMap, RejectsBadInput) {
  PointCloud scan;
  EXPECT_THROW(extractPlanes({&scan}, {}, PlaneSettings{}), Error);
  EXPECT_THROW(extractPlanes({nullptr}, {Pose()}, PlaneSettings{}), Error);
  PlaneSettings bad;
  bad.voxel_size = -1.0;
  EXPECT_THROW(extractPlanes({&scan}, {Pose()}, bad), Error);
  EXPECT_TRUE(extractPlanes({&scan}, {Pose()}, PlaneSettings{}).empty());
}

}  // namespace
}  // namespace hba::voxel
