// The procedural town: ground, kerbs, buildings, walls, poles, trees, bushes.
#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>

#include "corridor.hpp"
#include "hba/core/error.hpp"
#include "hba/sim/world.hpp"
#include "mesh_builder.hpp"
#include "path_clearance.hpp"
#include "path_samples.hpp"
#include "sim/random.hpp"

namespace hba::sim {
namespace {

using Vec2 = Eigen::Vector2d;

// The clearance raster is exact only at cell centres: keep this much extra room.
constexpr double kRasterSlack = 0.75;
// Objects sink this far into the ground so that slopes never show a gap below them.
constexpr double kFoundationDepth = 0.5;

class WorldBuilder {
 public:
  WorldBuilder(const std::vector<Pose>& path, const Terrain& terrain, const WorldConfig& config,
               std::uint64_t seed)
      : path_(path),
        terrain_(terrain),
        config_(config),
        clearance_(path, config.populated_distance + 5.0, config.margin),
        rng_(makeRng(seed, Stream::World)) {}

  World build() {
    addGround();
    if (config_.indoor) {
      addCorridor(path_, terrain_, clearance_, rng_, mesh_);
    } else {
      addKerbs();
    }
    const auto populated = clearance_.cellsBetween(0.0, config_.populated_distance);
    const double area_units = populated.size() * clearance_.cell() * clearance_.cell() / 1e4;
    // Each object class draws from its own band of distances from the path.
    place(config_.buildings * area_units, config_.corridor, config_.populated_distance,
          [this](const Vec2& c) { return tryBuilding(c); });
    place(config_.walls * area_units, config_.corridor, config_.populated_distance,
          [this](const Vec2& c) { return tryWall(c); });
    place(config_.poles * area_units, config_.road_half_width + 0.8, config_.corridor + 4.0,
          [this](const Vec2& c) { return tryPole(c); });
    place(config_.trees * area_units, config_.road_half_width + 2.0, config_.populated_distance,
          [this](const Vec2& c) { return tryTree(c); });
    place(config_.bushes * area_units, config_.road_half_width + 2.5, config_.populated_distance,
          [this](const Vec2& c) { return tryBush(c); });
    return World(std::move(mesh_.triangles()), std::move(spheres_));
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  float reflectivity(double lo, double hi) { return static_cast<float>(uniform(lo, hi)); }
  // Draws in a fixed order (the order of function arguments is unspecified).
  Vec2 uniformOffset(double half) {
    const double x = uniform(-half, half);
    return Vec2(x, uniform(-half, half));
  }
  Vec3 gaussianVector(double sigma) {
    std::normal_distribution<double> gaussian(0.0, sigma);
    const double x = gaussian(rng_);
    const double y = gaussian(rng_);
    return Vec3(x, y, gaussian(rng_));
  }

  void addGround() {
    const Vec2 lo = clearance_.minCorner(), hi = clearance_.maxCorner();
    const double cell = config_.ground_cell;
    const auto nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell));
    const auto ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell));
    auto vertex = [&](int i, int j) {
      const double x = lo.x() + i * cell, y = lo.y() + j * cell;
      return Vec3(x, y, terrain_.height(x, y));
    };
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        // Asphalt near the path, duller earth and grass farther out.
        const Vec2 c = lo + cell * Vec2(i + 0.5, j + 0.5);
        const bool road = clearance_.clearance(c.x(), c.y()) < config_.road_half_width;
        const float r = road ? 0.12f : 0.22f;
        mesh_.addQuad(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1), r);
      }
    }
  }

  // Kerb stones left and right of the road, skipped where another stretch of
  // road runs (crossings, the lanes of the street) or a kerb already stands
  // (laps and revisits drive the same road again).
  void addKerbs() {
    constexpr double kStone = 2.0, kHeight = 0.15, kWidth = 0.25;
    std::unordered_map<std::int64_t, std::vector<Vec2>> placed;  // by kStone-sized cell
    auto cellKey = [&](const Vec2& p, int dx, int dy) {
      const auto x = static_cast<std::int64_t>(std::floor(p.x() / kStone)) + dx;
      const auto y = static_cast<std::int64_t>(std::floor(p.y() / kStone)) + dy;
      return x * 73856093 ^ y * 19349663;
    };
    auto occupied = [&](const Vec2& p) {
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const auto it = placed.find(cellKey(p, dx, dy));
          if (it == placed.end()) continue;
          for (const Vec2& q : it->second) {
            if ((p - q).norm() < 0.9 * kStone) return true;
          }
        }
      }
      return false;
    };
    for (const PathSample& sample : samplePath(path_, kStone)) {
      for (double side : {-1.0, 1.0}) {
        const Vec2 c = sample.position + side * config_.road_half_width * sample.left;
        if (clearance_.clearance(c.x(), c.y()) < config_.road_half_width - kRasterSlack) continue;
        if (occupied(c)) continue;
        placed[cellKey(c, 0, 0)].push_back(c);
        const double ground = terrain_.height(c.x(), c.y());
        mesh_.addBox(c, ground - 0.1, kStone, kWidth, kHeight + 0.1, sample.yaw, 0.35f);
      }
    }
  }

  void place(double count, double near, double far, const std::function<bool(const Vec2&)>& fn) {
    const auto candidates = clearance_.cellsBetween(near, far);
    if (candidates.empty()) return;
    const auto wanted = static_cast<std::size_t>(std::lround(count));
    std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
    std::size_t placed = 0;
    for (std::size_t attempt = 0; attempt < 20 * wanted && placed < wanted; ++attempt) {
      const double half = 0.5 * clearance_.cell();
      const Vec2& cell = candidates[pick(rng_)];
      const Vec2 c = cell + uniformOffset(half);
      if (fn(c)) ++placed;
    }
  }

  // True if every point of the turned rectangle is at least `needed` from the path.
  bool footprintClear(const Vec2& center, double length, double width, double yaw, double needed) const {
    const Vec2 along(std::cos(yaw), std::sin(yaw)), across(-along.y(), along.x());
    const int nl = static_cast<int>(std::ceil(length)) + 1, nw = static_cast<int>(std::ceil(width)) + 1;
    for (int i = 0; i <= nl; ++i) {
      for (int j = 0; j <= nw; ++j) {
        const Vec2 p =
            center + (i / double(nl) - 0.5) * length * along + (j / double(nw) - 0.5) * width * across;
        if (clearance_.clearance(p.x(), p.y()) < needed + kRasterSlack) return false;
      }
    }
    return true;
  }

  // Lowest ground under a footprint, so the object never floats.
  double baseUnder(const Vec2& center, double radius) const {
    double z = terrain_.height(center.x(), center.y());
    for (int i = 0; i < 8; ++i) {
      const double a = M_PI / 4 * i;
      const Vec2 p = center + radius * Vec2(std::cos(a), std::sin(a));
      z = std::min(z, terrain_.height(p.x(), p.y()));
    }
    return z - kFoundationDepth;
  }

  // Mostly aligned with the street like a real block, sometimes at any angle.
  double objectYaw(const Vec2& c, double aligned_probability) {
    if (chance(aligned_probability)) {
      return clearance_.heading(c.x(), c.y()) + uniform(-0.08, 0.08);
    }
    return uniform(0.0, M_PI);
  }

  bool tryBuilding(const Vec2& c) {
    const double length = uniform(6.0, 24.0);
    const double width = uniform(6.0, 16.0);
    const double yaw = objectYaw(c, 0.6);
    if (!footprintClear(c, length, width, yaw, config_.corridor)) return false;
    const double base = baseUnder(c, 0.5 * std::hypot(length, width));
    const double height = uniform(4.0, 20.0);
    mesh_.addBox(c, base, length, width, height + kFoundationDepth, yaw, reflectivity(0.2, 0.75));
    return true;
  }

  bool tryWall(const Vec2& c) {
    const double length = uniform(6.0, 30.0), thickness = 0.3;
    const double yaw = objectYaw(c, 0.7);
    if (!footprintClear(c, length, thickness, yaw, config_.corridor - 0.5)) return false;
    const double base = baseUnder(c, 0.5 * length);
    const double height = uniform(1.2, 3.0);
    mesh_.addBox(c, base, length, thickness, height + kFoundationDepth, yaw, reflectivity(0.25, 0.6));
    return true;
  }

  bool tryPole(const Vec2& c) {
    const double base = baseUnder(c, 0.2);
    const double radius = uniform(0.08, 0.2);
    const double height = uniform(4.0, 9.0);
    mesh_.addPrism(c, base, radius, height, 8, reflectivity(0.5, 0.9));
    return true;
  }

  // A trunk crowned with foliage: random small triangles and a few spheres,
  // so that some of the world is scattered and far from planar.
  bool tryTree(const Vec2& c) {
    const double crown_radius = uniform(1.2, 2.5);
    // Foliage reaches ~1.7 crown radii from the trunk: keep it off the road.
    const double needed = config_.road_half_width + 0.5 + 1.7 * crown_radius + kRasterSlack;
    if (clearance_.clearance(c.x(), c.y()) < needed) return false;
    const double base = baseUnder(c, 0.3);
    const double trunk = uniform(2.0, 4.0);
    const double trunk_radius = uniform(0.1, 0.25);
    mesh_.addPrism(c, base, trunk_radius, trunk + kFoundationDepth, 6, 0.3f);
    const Vec3 crown(c.x(), c.y(), base + kFoundationDepth + trunk + 0.8 * crown_radius);
    const float leaves = reflectivity(0.4, 0.6);
    for (int i = 0; i < 40; ++i) {
      // A leaf: a small random triangle somewhere inside the crown.
      const Vec3 direction = gaussianVector(1.0).normalized();
      const Vec3 centre = crown + direction * crown_radius * std::cbrt(uniform(0.0, 1.0));
      const Vec3 a = centre + gaussianVector(0.25);
      const Vec3 b = centre + gaussianVector(0.25);
      const Vec3 c3 = centre + gaussianVector(0.25);
      mesh_.addTriangle(a, b, c3, leaves);
    }
    for (int i = 0; i < 3; ++i) {
      const Vec3 offset = 0.4 * crown_radius * gaussianVector(1.0).normalized();
      spheres_.push_back(Sphere{crown + offset, 0.45 * crown_radius, leaves});
    }
    return true;
  }

  bool tryBush(const Vec2& c) {
    const double ground = terrain_.height(c.x(), c.y());
    const int blobs = static_cast<int>(uniform(2.0, 6.0));
    const float leaves = reflectivity(0.35, 0.55);
    for (int i = 0; i < blobs; ++i) {
      const double r = uniform(0.3, 0.8);
      const Vec2 p = c + uniformOffset(0.8);
      spheres_.push_back(Sphere{Vec3(p.x(), p.y(), ground + 0.4 * r), r, leaves});
    }
    return true;
  }

  const std::vector<Pose>& path_;
  const Terrain& terrain_;
  WorldConfig config_;
  PathClearance clearance_;
  std::mt19937_64 rng_;
  MeshBuilder mesh_;
  std::vector<Sphere> spheres_;
};

}  // namespace

World buildWorld(const std::vector<Pose>& path, const Terrain& terrain, const WorldConfig& config,
                 std::uint64_t seed) {
  if (path.empty()) throw Error("simulate: cannot build a world around an empty path");
  if (!(config.ground_cell > 0.0)) throw Error("simulate: the ground cell must be positive");
  return WorldBuilder(path, terrain, config, seed).build();
}

}  // namespace hba::sim
