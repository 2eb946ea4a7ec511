// Ray/primitive intersections and the BVH against brute force.
#include <gtest/gtest.h>

#include <random>

#include "hba/sim/bvh.hpp"
#include "hba/sim/primitives.hpp"

namespace hba::sim {
namespace {

TEST(SimPrimitives, RayHitsTriangleAtTheRightDistance) {
  const Triangle t{Vec3(5, -1, -1), Vec3(5, 1, -1), Vec3(5, 0, 2), 0.5f};
  const Ray ray{Vec3::Zero(), Vec3::UnitX()};
  const auto hit = intersect(ray, t, 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 5.0, 1e-12);
  EXPECT_FALSE(intersect(ray, t, 4.0).has_value()) << "beyond t_max";
  EXPECT_FALSE(intersect(Ray{Vec3::Zero(), -Vec3::UnitX()}, t, 100.0).has_value()) << "behind";
  EXPECT_FALSE(intersect(Ray{Vec3(0, 3, 0), Vec3::UnitX()}, t, 100.0).has_value()) << "beside";
}

TEST(SimPrimitives, RayHitsSphereFromOutsideAndInside) {
  const Sphere s{Vec3(10, 0, 0), 2.0, 0.5f};
  const auto outside = intersect(Ray{Vec3::Zero(), Vec3::UnitX()}, s, 100.0);
  ASSERT_TRUE(outside.has_value());
  EXPECT_NEAR(*outside, 8.0, 1e-12);
  const auto inside = intersect(Ray{Vec3(10, 0, 0), Vec3::UnitY()}, s, 100.0);
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR(*inside, 2.0, 1e-12);
  EXPECT_FALSE(intersect(Ray{Vec3::Zero(), Vec3::UnitY()}, s, 100.0).has_value());
}

TEST(SimBvh, ClosestHitMatchesBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> position(-20.0, 20.0), offset(-1.5, 1.5);
  std::vector<Triangle> triangles;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 c(position(rng), position(rng), position(rng));
    Triangle t;
    t.a = c + Vec3(offset(rng), offset(rng), offset(rng));
    t.b = c + Vec3(offset(rng), offset(rng), offset(rng));
    t.c = c + Vec3(offset(rng), offset(rng), offset(rng));
    triangles.push_back(t);
  }
  std::vector<Aabb> bounds;
  for (const Triangle& t : triangles) bounds.push_back(t.bounds());
  const Bvh bvh(bounds);
  EXPECT_GT(bvh.nodeCount(), 100u);

  std::normal_distribution<double> gaussian(0.0, 1.0);
  int hits = 0;
  for (int r = 0; r < 2000; ++r) {
    const Ray ray{Vec3(position(rng), position(rng), position(rng)),
                  Vec3(gaussian(rng), gaussian(rng), gaussian(rng)).normalized()};
    std::optional<double> brute;
    for (const Triangle& t : triangles) {
      if (auto d = intersect(ray, t, brute.value_or(1e9))) brute = d;
    }
    const auto fast = bvh.closestHit(
        ray, 1e9, [&](std::uint32_t i, double t_max) { return intersect(ray, triangles[i], t_max); });
    ASSERT_EQ(fast.has_value(), brute.has_value()) << "ray " << r;
    if (fast) {
      ++hits;
      EXPECT_DOUBLE_EQ(fast->distance, *brute) << "ray " << r;
    }
  }
  EXPECT_GT(hits, 200);
}

}  // namespace
}  // namespace hba::sim
