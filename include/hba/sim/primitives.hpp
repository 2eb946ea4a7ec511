#pragma once
// The shapes a synthetic world is made of, and exact ray intersections.
// Everything is double precision so that a noise-free hit lies on its
// surface to ~1e-9 m even 100 m away from the sensor.
#include <limits>
#include <optional>

#include "hba/core/types.hpp"

namespace hba::sim {

struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();  // unit length
};

// An axis-aligned box; empty() until a point is added.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void grow(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void grow(const Aabb& box) {
    min = min.cwiseMin(box.min);
    max = max.cwiseMax(box.max);
  }
  bool empty() const { return (min.array() > max.array()).any(); }
  Vec3 center() const { return 0.5 * (min + max); }
  double surfaceArea() const;
  // Slab test against a ray given by origin and 1/direction; true if the box
  // is entered before t_max (and after 0).
  bool hitBefore(const Vec3& origin, const Vec3& inverse_direction, double t_max) const;
};

// A one-sided-agnostic triangle with the reflectivity of its surface (0..1).
struct Triangle {
  Vec3 a, b, c;
  float reflectivity = 0.3f;

  Aabb bounds() const;
  Vec3 normal() const { return (b - a).cross(c - a).normalized(); }
};

// A sphere, for non-planar clutter (bushes, foliage).
struct Sphere {
  Vec3 center = Vec3::Zero();
  double radius = 0.5;
  float reflectivity = 0.5f;

  Aabb bounds() const;
};

// Distance along the ray to the first intersection in (0, t_max), if any.
std::optional<double> intersect(const Ray& ray, const Triangle& triangle, double t_max);
std::optional<double> intersect(const Ray& ray, const Sphere& sphere, double t_max);

}  // namespace hba::sim
