#include "corridor.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "path_samples.hpp"

namespace hba::sim {
namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kSample = 1.0;       // m between wall pieces
constexpr double kBelowFloor = 0.3;   // walls reach below the floor: no gap on slopes
constexpr double kRasterSlack = 1.0;  // the clearance raster is exact at cell centres only

// One stretch of corridor: its walls' distances from the path, its ceiling
// height above the floor and the walls' reflectivity.
struct Stretch {
  double left = 2.0;
  double right = 2.0;
  double ceiling = 3.0;
  float reflectivity = 0.4f;
  double length = 10.0;  // m of path it lasts
};

class CorridorBuilder {
 public:
  CorridorBuilder(const Terrain& terrain, const PathClearance& clearance, std::mt19937_64& rng,
                  MeshBuilder& mesh)
      : terrain_(terrain), clearance_(clearance), rng_(rng), mesh_(mesh) {}

  void build(const std::vector<Pose>& path) {
    std::vector<Sample> samples = resample(path);
    if (samples.size() < 2) return;
    const std::vector<bool> revisit = revisits(samples);
    Stretch stretch = nextStretch();
    double into_stretch = 0.0;
    for (std::size_t k = 1; k < samples.size(); ++k) {
      const Sample& a = samples[k - 1];
      const Sample& b = samples[k];
      // Built on the first pass; two pieces run on into the revisit, so that
      // the corridor closes where a lap meets its start.
      if (revisit[k] && revisit[k - 1] && (k < 2 || revisit[k - 2])) continue;
      into_stretch += kSample;
      if (into_stretch > stretch.length) {
        const Stretch next = nextStretch();
        addJog(a, stretch, next);
        stretch = next;
        into_stretch = 0.0;
      }
      for (const double side : {1.0, -1.0}) addWallPiece(a, b, stretch, side);
      addCeilingPiece(a, b, stretch);
    }
  }

 private:
  struct Sample {
    Vec2 position;
    Vec2 left;  // unit, to the left of the direction of travel
    double floor = 0.0;
  };

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }

  // The path every kSample metres of travel (planar), with its left normal.
  std::vector<Sample> resample(const std::vector<Pose>& path) const {
    std::vector<Sample> out;
    for (const PathSample& s : samplePath(path, kSample)) {
      out.push_back({s.position, s.left, terrain_.height(s.position.x(), s.position.y())});
    }
    return out;
  }

  // Samples where the path comes back to a place it passed earlier (a lap,
  // a revisit): the corridor is built once, on the first pass.
  static std::vector<bool> revisits(const std::vector<Sample>& samples) {
    constexpr double kCell = 2.0, kSame = 1.5, kGone = 10.0;  // m
    auto key = [&](const Vec2& p, int dx, int dy) {
      const auto x = static_cast<std::int64_t>(std::floor(p.x() / kCell)) + dx;
      const auto y = static_cast<std::int64_t>(std::floor(p.y() / kCell)) + dy;
      return x * 73856093 ^ y * 19349663;
    };
    std::unordered_map<std::int64_t, std::vector<std::size_t>> seen;
    std::vector<bool> out(samples.size(), false);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const Vec2& p = samples[k].position;
      for (int dx = -1; dx <= 1 && !out[k]; ++dx) {
        for (int dy = -1; dy <= 1 && !out[k]; ++dy) {
          const auto it = seen.find(key(p, dx, dy));
          if (it == seen.end()) continue;
          for (const std::size_t j : it->second) {
            // Samples are kSample apart along the path.
            if ((samples[j].position - p).norm() < kSame && (k - j) * kSample > kGone) {
              out[k] = true;
              break;
            }
          }
        }
      }
      seen[key(p, 0, 0)].push_back(k);
    }
    return out;
  }

  Stretch nextStretch() {
    Stretch s;
    // Narrow corridors (1.4 m to the wall) to halls (6 m), not always centred.
    const bool hall = chance(0.25);
    s.left = hall ? uniform(3.5, 6.0) : uniform(1.4, 2.6);
    s.right = hall ? uniform(3.5, 6.0) : uniform(1.4, 2.6);
    s.ceiling = hall ? uniform(4.0, 7.0) : uniform(2.6, 3.4);
    s.reflectivity = static_cast<float>(uniform(0.3, 0.8));
    s.length = uniform(8.0, 30.0);
    return s;
  }

  Vec3 at(const Sample& s, double offset, double height) const {
    const Vec2 p = s.position + offset * s.left;
    return Vec3(p.x(), p.y(), s.floor + height);
  }

  // A wall point is kept only if no other stretch of the path runs closer to it.
  bool free(const Sample& s, double offset) const {
    const Vec2 p = s.position + offset * s.left;
    return clearance_.clearance(p.x(), p.y()) > std::abs(offset) - kRasterSlack;
  }

  void addWallPiece(const Sample& a, const Sample& b, const Stretch& stretch, double side) {
    const double offset = side * (side > 0 ? stretch.left : stretch.right);
    if (!free(a, offset) || !free(b, offset)) return;
    const double top = stretch.ceiling;
    if (chance(0.06)) {  // a door niche: the wall steps back, and its sides show
      const double back = offset + side * uniform(0.3, 1.0);
      if (!free(a, back) || !free(b, back)) return;
      mesh_.addQuad(at(a, back, -kBelowFloor), at(b, back, -kBelowFloor), at(b, back, top), at(a, back, top),
                    stretch.reflectivity);
      for (const Sample* s : {&a, &b}) {
        mesh_.addQuad(at(*s, offset, -kBelowFloor), at(*s, back, -kBelowFloor), at(*s, back, top),
                      at(*s, offset, top), stretch.reflectivity);
      }
      return;
    }
    mesh_.addQuad(at(a, offset, -kBelowFloor), at(b, offset, -kBelowFloor), at(b, offset, top),
                  at(a, offset, top), stretch.reflectivity);
    if (chance(0.08)) {  // a pillar or a cabinet against the wall
      const bool pillar = chance(0.5);
      const double depth = pillar ? uniform(0.3, 0.6) : uniform(0.4, 0.8);
      const double width = pillar ? depth : uniform(0.6, 1.6);
      const double height = pillar ? top + kBelowFloor : uniform(0.8, 2.0);
      const Vec2 c = a.position + (offset - side * 0.5 * depth) * a.left;
      const double yaw = std::atan2(a.left.x(), -a.left.y());  // along the path
      mesh_.addBox(c, a.floor - kBelowFloor, width, depth, height, yaw,
                   static_cast<float>(uniform(0.2, 0.9)));
    }
  }

  void addCeilingPiece(const Sample& a, const Sample& b, const Stretch& stretch) {
    const double h = stretch.ceiling;
    mesh_.addQuad(at(a, stretch.left, h), at(b, stretch.left, h), at(b, -stretch.right, h),
                  at(a, -stretch.right, h), 0.3f);
  }

  // Where one stretch meets the next: the walls step in or out, and the
  // ceiling steps up or down, across the corridor.
  void addJog(const Sample& s, const Stretch& from, const Stretch& to) {
    const double top = std::max(from.ceiling, to.ceiling);
    for (const double side : {1.0, -1.0}) {
      const double o0 = side * (side > 0 ? from.left : from.right);
      const double o1 = side * (side > 0 ? to.left : to.right);
      if (!free(s, o0) || !free(s, o1)) continue;
      mesh_.addQuad(at(s, o0, -kBelowFloor), at(s, o1, -kBelowFloor), at(s, o1, top), at(s, o0, top),
                    to.reflectivity);
    }
    const double wide_left = std::max(from.left, to.left);
    const double wide_right = std::max(from.right, to.right);
    mesh_.addQuad(at(s, wide_left, from.ceiling), at(s, -wide_right, from.ceiling),
                  at(s, -wide_right, to.ceiling), at(s, wide_left, to.ceiling), 0.3f);
  }

  const Terrain& terrain_;
  const PathClearance& clearance_;
  std::mt19937_64& rng_;
  MeshBuilder& mesh_;
};

}  // namespace

void addCorridor(const std::vector<Pose>& path, const Terrain& terrain, const PathClearance& clearance,
                 std::mt19937_64& rng, MeshBuilder& mesh) {
  CorridorBuilder(terrain, clearance, rng, mesh).build(path);
}

}  // namespace hba::sim
