// The procedural world: a free corridor along the path, varied content,
// determinism.
#include <gtest/gtest.h>

#include "hba/sim/world.hpp"
#include "sim_test_world.hpp"

namespace hba::sim {
namespace {

// Nothing may stand on the road: rays along the path, at several heights and
// lateral offsets inside the corridor, reach the next pose unobstructed.
TEST(SimWorld, ThePathStaysFree) {
  const Simulation& s = test::smallSimulation();
  const auto& poses = s.truth.poses;
  for (std::size_t k = 0; k + 1 < poses.size(); ++k) {
    const Vec3 step = poses[k + 1].t - poses[k].t;
    const Vec3 left = poses[k].R().col(1);
    for (double height : {-1.3, 0.0, 1.5}) {  // relative to the 1.8 m sensor
      for (double lateral : {-1.0, 0.0, 1.0}) {
        const Ray ray{poses[k].t + Vec3(0, 0, height) + lateral * left, step.normalized()};
        const auto hit = s.world.intersect(ray, step.norm());
        EXPECT_FALSE(hit.has_value()) << "frame " << k << " height " << height << " lateral " << lateral;
      }
    }
  }
}

TEST(SimWorld, TheSensorRidesAboveTheGround) {
  const Simulation& s = test::smallSimulation();
  for (std::size_t k = 0; k < s.truth.size(); k += 10) {
    const Ray down{s.truth.poses[k].t, -Vec3::UnitZ()};
    const auto hit = s.world.intersect(down, 10.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance, 1.8, 0.01) << "frame " << k;
  }
}

TEST(SimWorld, HoldsStructuresAndNonPlanarClutter) {
  const Simulation& s = test::smallSimulation();
  EXPECT_GT(s.world.spheres().size(), 20u);
  // Tall things (buildings, poles, trees) exist around the path.
  std::size_t tall = 0;
  for (const Triangle& t : s.world.triangles()) {
    const double ground = s.terrain.height(t.a.x(), t.a.y());
    if (std::max({t.a.z(), t.b.z(), t.c.z()}) > ground + 4.0) ++tall;
  }
  EXPECT_GT(tall, 200u);
}

TEST(SimWorld, SameSeedSameWorldOtherSeedOtherWorld) {
  const Simulation& s = test::smallSimulation();
  const World again = buildWorld(s.truth.poses, s.terrain, s.config.world, s.config.seed);
  ASSERT_EQ(again.triangles().size(), s.world.triangles().size());
  EXPECT_EQ(again.triangles().back().a, s.world.triangles().back().a);
  const World other = buildWorld(s.truth.poses, s.terrain, s.config.world, s.config.seed + 1);
  EXPECT_TRUE(other.triangles().size() != s.world.triangles().size() ||
              other.triangles().back().a != s.world.triangles().back().a);
}

// Scene presets: a city block holds far more building faces than an open,
// vegetated scene, which holds far more foliage.
TEST(SimWorld, ScenesDifferInStructureAndVegetation) {
  const Simulation& s = test::smallSimulation();
  const World city = buildWorld(s.truth.poses, s.terrain, scenePreset(Scene::City), s.config.seed);
  const World open = buildWorld(s.truth.poses, s.terrain, scenePreset(Scene::Open), s.config.seed);
  std::size_t city_tall = 0, open_tall = 0;
  for (const auto* w : {&city, &open}) {
    for (const Triangle& t : w->triangles()) {
      const double ground = s.terrain.height(t.a.x(), t.a.y());
      const bool tall = std::min({t.a.z(), t.b.z(), t.c.z()}) > ground + 6.0 &&
                        (t.b - t.a).cross(t.c - t.a).norm() > 2.0;  // big faces: walls, roofs
      if (tall) ++(w == &city ? city_tall : open_tall);
    }
  }
  EXPECT_GT(city_tall, 5 * std::max<std::size_t>(open_tall, 1));
  EXPECT_GT(open.spheres().size(), 2 * city.spheres().size());
  EXPECT_EQ(findEnum<Scene>("open"), Scene::Open);
  EXPECT_FALSE(findEnum<Scene>("forest"));
  EXPECT_EQ(hba::toString(Scene::City), "city");
}

// Indoors the path runs in a closed corridor: the path stays free, a
// ceiling is overhead and walls stand within a hall's width on both sides
// nearly everywhere (door niches and crossings leave gaps), on a flat floor.
TEST(SimWorld, IndoorSceneEnclosesThePath) {
  SimulationConfig config;
  config.seed = 7;
  config.trajectory.frames = 400;  // more than one lap: revisits are built once
  config.scene = Scene::Indoor;
  config.world = scenePreset(Scene::Indoor);
  const Simulation s = prepareSimulation(config);
  EXPECT_TRUE(s.world.spheres().empty());  // no vegetation
  const auto& poses = s.truth.poses;
  std::size_t enclosed = 0, checked = 0;
  for (std::size_t k = 0; k + 1 < poses.size(); k += 5) {
    const Vec3 step = poses[k + 1].t - poses[k].t;
    EXPECT_FALSE(s.world.intersect(Ray{poses[k].t, step.normalized()}, step.norm())) << "frame " << k;
    EXPECT_NEAR(poses[k].t.z(), 1.8, 1e-9) << "frame " << k;  // flat floor
    const auto up = s.world.intersect(Ray{poses[k].t, Vec3::UnitZ()}, 20.0);
    const Vec3 left = poses[k].R().col(1);
    const auto l = s.world.intersect(Ray{poses[k].t, left}, 20.0);
    const auto r = s.world.intersect(Ray{poses[k].t, -left}, 20.0);
    ++checked;
    if (up && up->distance < 6.0 && l && l->distance < 7.5 && r && r->distance < 7.5) ++enclosed;
  }
  EXPECT_GT(enclosed, 0.85 * static_cast<double>(checked)) << enclosed << " of " << checked;
  EXPECT_EQ(findEnum<Scene>("indoor"), Scene::Indoor);
  EXPECT_EQ(hba::toString(Scene::Indoor), "indoor");
}

TEST(SimWorld, TerrainSlopesStayGentle) {
  const Terrain terrain(11, 0.03);
  double steepest = 0.0, lowest = 1e9, highest = -1e9;
  for (double x = -500; x <= 500; x += 10) {
    for (double y = -500; y <= 500; y += 10) {
      steepest = std::max(steepest, terrain.gradient(x, y).norm());
      lowest = std::min(lowest, terrain.height(x, y));
      highest = std::max(highest, terrain.height(x, y));
    }
  }
  EXPECT_LE(steepest, 0.03 + 1e-12);
  EXPECT_GT(steepest, 0.01);
  EXPECT_GT(highest - lowest, 0.5) << "not flat";
  // The analytic gradient is the height's derivative.
  const double h = 1e-4;
  const Eigen::Vector2d numeric((terrain.height(3 + h, 4) - terrain.height(3 - h, 4)) / (2 * h),
                                (terrain.height(3, 4 + h) - terrain.height(3, 4 - h)) / (2 * h));
  EXPECT_NEAR((numeric - terrain.gradient(3, 4)).norm(), 0.0, 1e-8);
}

}  // namespace
}  // namespace hba::sim
