#include <gtest/gtest.h>

#include <random>

#include <tbb/global_control.h>
#include <Eigen/Eigenvalues>

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
  const PlaneExtraction found = extractPlanes(pointers(scans), {Pose(), Pose()}, settings);
  ASSERT_EQ(found.planes.size(), 1u);
  EXPECT_EQ(found.planes[0].depth, 0);
  const std::vector<PointRef> points = found.pointsOf(found.planes[0]);
  EXPECT_EQ(points.size(), 400u);
  EXPECT_EQ(points.front().frame, 0u);
  EXPECT_EQ(points.back().frame, 1u);
  EXPECT_EQ(points.back().index, 199u);
  ASSERT_EQ(found.planes[0].clusters.size(), 2u);
  EXPECT_EQ(found.planes[0].clusters[1].frame, 1u);
  EXPECT_EQ(found.planes[0].clusters[1].count(), 200.0);
}

TEST(PlaneMap, PosesPlaceTheScansInTheWorld) {
  // Frame 1 sees the same wall from 1 m further: only with its pose do the
  // two scans share one plane.
  std::mt19937 rng(2);
  std::vector<PointCloud> scans(2);
  addSquare(scans[0], rng, 2, 1.0f, 0.2f, 3.8f, 200);
  addSquare(scans[1], rng, 2, 0.0f, 0.2f, 3.8f, 200);
  const Pose shifted(Quat::Identity(), Vec3(0, 0, 1));
  EXPECT_EQ(extractPlanes(pointers(scans), {Pose(), shifted}, PlaneSettings{}).planes.size(), 1u);
  EXPECT_TRUE(extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{}).planes.empty());
}

TEST(PlaneMap, PlaneSeenByOneFrameIsDropped) {
  std::mt19937 rng(3);
  std::vector<PointCloud> scans(2);
  addSquare(scans[0], rng, 2, 1.0f, 0.2f, 3.8f, 200);
  addSquare(scans[1], rng, 0, 9.0f, 8.2f, 11.8f, 200);  // elsewhere
  EXPECT_TRUE(extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{}).planes.empty());
  PlaneSettings single;
  single.min_frames = 1;
  EXPECT_EQ(extractPlanes(pointers(scans), {Pose(), Pose()}, single).planes.size(), 2u);
}

// The frame count stops as soon as it reaches min_frames: a plane one frame
// short is still dropped, and one that reaches it kept with all its frames.
TEST(PlaneMap, PlaneNeedsMinFramesFrames) {
  std::mt19937 rng(5);
  std::vector<PointCloud> scans(4);
  for (int f = 0; f < 2; ++f) addSquare(scans[f], rng, 2, 1.0f, 0.2f, 3.8f, 200);   // two frames
  for (int f = 0; f < 4; ++f) addSquare(scans[f], rng, 2, 9.0f, 8.2f, 11.8f, 200);  // four
  const std::vector<Pose> poses(4);
  PlaneSettings three;
  three.min_frames = 3;
  const PlaneExtraction found = extractPlanes(pointers(scans), poses, three);
  ASSERT_EQ(found.planes.size(), 1u);
  EXPECT_EQ(found.planes.front().clusters.size(), 4u);
  three.min_frames = 2;
  EXPECT_EQ(extractPlanes(pointers(scans), poses, three).planes.size(), 2u);
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
  const PlaneExtraction found = extractPlanes(pointers(scans), {Pose(), Pose()}, PlaneSettings{});
  ASSERT_GE(found.planes.size(), 4u);
  std::size_t covered = 0;
  for (const auto& plane : found.planes) {
    EXPECT_GE(plane.depth, 1);
    int floor = 0, wall = 0;
    for (const PointRef& r : found.pointsOf(plane)) {
      const Vec3f& p = scans[r.frame].points[r.index];
      (p.z() == 1.0f && p.x() != 1.5f ? floor : wall) += 1;
    }
    EXPECT_TRUE(floor == 0 || wall == 0) << floor << " floor, " << wall << " wall points";
    covered += plane.pointCount();
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
  EXPECT_TRUE(extractPlanes(pointers(line), {Pose(), Pose()}, PlaneSettings{}).planes.empty());
  EXPECT_TRUE(extractPlanes(pointers(blob), {Pose(), Pose()}, PlaneSettings{}).planes.empty());
}

// The same planes, points and clusters, bit for bit.
void expectSameFeatures(const PlaneExtraction& a, const PlaneExtraction& b) {
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (std::size_t p = 0; p < a.planes.size(); ++p) {
    EXPECT_EQ(a.planes[p].depth, b.planes[p].depth);
    const std::vector<PointRef> pa = a.pointsOf(a.planes[p]), pb = b.pointsOf(b.planes[p]);
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t k = 0; k < pa.size(); ++k) {
      EXPECT_EQ(pa[k].frame, pb[k].frame);
      EXPECT_EQ(pa[k].index, pb[k].index);
    }
    ASSERT_EQ(a.planes[p].clusters.size(), b.planes[p].clusters.size());
    for (std::size_t k = 0; k < a.planes[p].clusters.size(); ++k) {
      const FrameCluster& ca = a.planes[p].clusters[k];
      const FrameCluster& cb = b.planes[p].clusters[k];
      EXPECT_EQ(ca.frame, cb.frame);
      EXPECT_EQ(ca.count(), cb.count());
      EXPECT_EQ(ca.mean(), cb.mean());
      EXPECT_EQ(ca.scatter(), cb.scatter());
    }
  }
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
  const PlaneExtraction one = run(1);
  const PlaneExtraction two = run(2);
  ASSERT_FALSE(one.planes.empty());
  expectSameFeatures(one, two);
}

// Four scans of six walls across and along the axes, far from the origin,
// turned off the axes, each frame a little apart.
struct FarWalls {
  std::vector<PointCloud> scans = std::vector<PointCloud>(4);
  std::vector<Pose> poses;
  explicit FarWalls(std::uint32_t seed) {
    std::mt19937 rng(seed);
    for (auto& s : scans) {
      for (int wall = 0; wall < 6; ++wall) addSquare(s, rng, wall % 3, 1.3f + 3.7f * wall, -9.f, 9.f, 3000);
    }
    for (int f = 0; f < 4; ++f) {
      poses.emplace_back(Quat(Eigen::AngleAxisd(0.3 + 0.001 * f, Vec3(0.3, 0.2, 1.0).normalized())),
                         Vec3(0.01 * f - 350.0, 0.005 * f + 1200.0, -0.002 * f));
    }
  }
};

TEST(PlaneMap, TwoVoxelsAtOnceGiveEachExtractionsPlanes) {
  const FarWalls walls(8);
  const std::vector<PointCloud>& scans = walls.scans;
  const std::vector<Pose>& poses = walls.poses;
  PlaneSettings coarse;
  coarse.voxel_size = 4.0;
  for (const double fine_voxel : {4.0, 2.0, 1.0, 1.5}) {  // 1.5: cells that do not nest
    PlaneSettings fine = coarse;
    fine.voxel_size = fine_voxel;
    const auto [both_coarse, both_fine] =
        extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, fine_voxel);
    ASSERT_FALSE(both_fine.planes.empty()) << fine_voxel;
    expectSameFeatures(both_coarse, extractPlanes(pointers(scans), poses, coarse));
    expectSameFeatures(both_fine, extractPlanes(pointers(scans), poses, fine));
  }
  EXPECT_THROW(extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, 8.0), Error);
  EXPECT_THROW(extractPlanesAtTwoVoxels(pointers(scans), poses, coarse, 0.0), Error);
}

TEST(PlaneMap, SharesOneAfterAnotherAreTheWholeExtraction) {
  // Walls across the x axis and along it (the cells of one wall in several
  // shares), turned, so that the shares' x ranges cut between planes' voxels.
  const FarWalls walls(10);
  const std::vector<PointCloud>& scans = walls.scans;
  const std::vector<Pose>& poses = walls.poses;
  PlaneSettings settings;
  settings.voxel_size = 1.0;
  const PlaneExtraction whole = extractPlanes(pointers(scans), poses, settings);
  ASSERT_GT(whole.planes.size(), 20u);
  for (const std::size_t shares : {1, 2, 3, 7}) {
    PlaneExtraction joined;
    joined.first_id = whole.first_id;
    std::size_t fewest = SIZE_MAX;
    for (std::size_t share = 0; share < shares; ++share) {
      PlaneExtraction part = extractPlanes(pointers(scans), poses, settings, share, shares);
      fewest = std::min(fewest, part.planes.size());
      // Each plane's points moved behind those joined so far.
      for (PlaneFeature& plane : part.planes) {
        joined.point_ids.insert(joined.point_ids.end(), part.point_ids.begin() + plane.first_point,
                                part.point_ids.begin() + plane.end_point);
        const std::uint32_t count = plane.end_point - plane.first_point;
        plane.first_point = static_cast<std::uint32_t>(joined.point_ids.size()) - count;
        plane.end_point = plane.first_point + count;
        joined.planes.push_back(std::move(plane));
      }
    }
    expectSameFeatures(whole, joined);
    EXPECT_GT(fewest, 0u) << shares << " shares: one is empty";
  }
  EXPECT_THROW(extractPlanes(pointers(scans), poses, settings, 2, 2), Error);
  EXPECT_THROW(extractPlanes(pointers(scans), poses, settings, 0, 0), Error);
}

TEST(PlaneMap, ClustersAreEachFramesPointsInItsOwnCoordinates) {
  // Each cluster must be what the frame's points of the plane sum to in the
  // scan's own coordinates, also 20 km from the origin, where a float world
  // coordinate is 2 mm coarse (the sums are taken near the scans instead).
  std::mt19937 rng(9);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<PointCloud> scans(3);
  for (auto& s : scans) {
    for (int wall = 0; wall < 4; ++wall) addSquare(s, rng, wall % 3, 1.3f + 3.7f * wall, -6.f, 6.f, 2000);
    for (Vec3f& p : s.points) p += Vec3f(noise(rng), noise(rng), noise(rng));
  }
  std::vector<Pose> poses;
  for (int f = 0; f < 3; ++f) {
    poses.emplace_back(Quat(Eigen::AngleAxisd(0.4 + 0.002 * f, Vec3(0.1, 0.3, 1.0).normalized())),
                       Vec3(20000.0 + 0.03 * f, -15000.0 - 0.02 * f, 31.0));
  }
  const PlaneExtraction found = extractPlanes(pointers(scans), poses, PlaneSettings{});
  ASSERT_GE(found.planes.size(), 4u);
  for (const PlaneFeature& plane : found.planes) {
    std::vector<PointCluster> direct(scans.size());
    for (const PointRef& r : found.pointsOf(plane))
      direct[r.frame].add(scans[r.frame].points[r.index].cast<double>());
    std::size_t observing = 0;
    for (const PointCluster& c : direct) observing += c.count > 0.0;
    ASSERT_EQ(plane.clusters.size(), observing);
    for (const FrameCluster& cluster : plane.clusters) {
      const PointCluster& expected = direct[cluster.frame];
      EXPECT_EQ(cluster.count(), expected.count);
      EXPECT_LT((cluster.mean() - expected.mean).norm(), 2e-5);
      // Float positions a few metres out round at a micrometre: the spread
      // within the plane agrees to a few millionths, across it (the cost,
      // 1 cm of noise) to 1e-3; a float 20 km out (2 mm) is 10 % off there.
      EXPECT_LT((cluster.scatter() - expected.scatter).norm(), 1e-5 * expected.scatter.norm());
      const Vec3 normal = Eigen::SelfAdjointEigenSolver<Mat3>(expected.scatter).eigenvectors().col(0);
      const double across = normal.dot(expected.scatter * normal);
      EXPECT_NEAR(normal.dot(cluster.scatter() * normal), across, 1e-3 * across);
    }
  }
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
  EXPECT_TRUE(extractPlanes({&scan}, {Pose()}, PlaneSettings{}).planes.empty());
}

}  // namespace
}  // namespace hba::voxel
