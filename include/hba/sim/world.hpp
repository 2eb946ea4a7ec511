#pragma once
// A static synthetic world: triangles and spheres with a BVH over them.
// Ray queries are const and safe to run from many threads at once.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/bvh.hpp"
#include "hba/sim/primitives.hpp"
#include "hba/sim/terrain.hpp"

namespace hba::sim {

struct SurfaceHit {
  double distance = 0.0;  // along the (unit) ray direction
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, facing the ray's origin
  float reflectivity = 0.0f;
  std::uint32_t primitive = 0;  // index: triangles first, then spheres
};

class World {
 public:
  World() = default;
  World(std::vector<Triangle> triangles, std::vector<Sphere> spheres);

  std::optional<SurfaceHit> intersect(const Ray& ray, double max_distance) const;

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }
  // Distance from `point` to the surface of primitive `index` (for tests).
  double distanceToPrimitive(std::uint32_t index, const Vec3& point) const;

 private:
  std::vector<Triangle> triangles_;
  std::vector<Sphere> spheres_;
  Bvh bvh_;
};

// What the procedural world contains. Densities are per 10 000 m^2 of the
// area around the path (within `populated_distance` of it).
struct WorldConfig {
  double max_slope = 0.03;           // terrain grade
  double ground_cell = 2.0;          // m, ground mesh resolution
  double margin = 60.0;              // m of ground beyond the path's bounding box
  double road_half_width = 3.5;      // kerbs stand here, left and right of the path
  double corridor = 5.0;             // m kept free of buildings and walls around the path
  double populated_distance = 40.0;  // objects are placed at most this far from the path
  double buildings = 30.0;
  double walls = 12.0;
  double poles = 25.0;
  double trees = 20.0;
  double bushes = 25.0;
  // Indoors: walls and a ceiling along the path instead of kerbs (see
  // corridor.hpp); the densities above still add objects beyond the walls.
  bool indoor = false;
};

// Scene kinds: densities of the world's objects.
//  - mixed: the default, buildings, walls, poles and vegetation;
//  - city: dense buildings and walls, little vegetation (a city block);
//  - open: a few buildings, mostly trees and bushes (a park, a campus lawn):
//    sparse structure, as in the scenes where local windows struggle;
//  - indoor: corridors and halls on a flat floor, under a ceiling: short
//    ranges, long walls nearly free along their axis.
enum class Scene { Mixed, City, Open, Indoor };
WorldConfig scenePreset(Scene scene);

// Builds terrain-following ground, kerbs along the path, buildings of varied
// size and orientation, walls, poles, trees (trunk + foliage of random small
// triangles and spheres) and bushes, never inside the free corridor around
// the path. Deterministic for a seed.
World buildWorld(const std::vector<Pose>& path, const Terrain& terrain, const WorldConfig& config,
                 std::uint64_t seed);

}  // namespace hba::sim

namespace hba {
template <>
struct EnumNames<sim::Scene> {
  static constexpr const char* what = "scene";
  static constexpr EnumName<sim::Scene> names[] = {{sim::Scene::Mixed, "mixed"},
                                                   {sim::Scene::City, "city"},
                                                   {sim::Scene::Open, "open"},
                                                   {sim::Scene::Indoor, "indoor"}};
};
}  // namespace hba
