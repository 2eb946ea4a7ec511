#include "hba/sim/primitives.hpp"

#include <algorithm>
#include <cmath>

namespace hba::sim {
namespace {
// Hits closer than this are self-intersections or the sensor's own housing.
constexpr double kMinHitDistance = 1e-6;
// Barycentric slack, so that a ray through a shared edge or vertex of a mesh
// never slips between its two triangles.
constexpr double kEdgeSlack = 1e-10;
}  // namespace

double Aabb::surfaceArea() const {
  if (empty()) return 0.0;
  const Vec3 d = max - min;
  return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

bool Aabb::hitBefore(const Vec3& origin, const Vec3& inverse_direction, double t_max) const {
  double t_enter = 0.0;
  double t_exit = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::isinf(inverse_direction[axis])) {
      // Parallel to this slab (0 * inf would give NaN): inside it or never.
      if (origin[axis] < min[axis] || origin[axis] > max[axis]) return false;
      continue;
    }
    double t0 = (min[axis] - origin[axis]) * inverse_direction[axis];
    double t1 = (max[axis] - origin[axis]) * inverse_direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
    if (t_enter > t_exit) return false;
  }
  return true;
}

Aabb Triangle::bounds() const {
  Aabb box;
  box.grow(a);
  box.grow(b);
  box.grow(c);
  return box;
}

Aabb Sphere::bounds() const {
  Aabb box;
  box.grow(center - Vec3::Constant(radius));
  box.grow(center + Vec3::Constant(radius));
  return box;
}

// Moller-Trumbore: solves origin + t d = a + u (b - a) + v (c - a).
std::optional<double> intersect(const Ray& ray, const Triangle& tri, double t_max) {
  const Vec3 edge1 = tri.b - tri.a;
  const Vec3 edge2 = tri.c - tri.a;
  const Vec3 p = ray.direction.cross(edge2);
  const double det = edge1.dot(p);
  if (std::abs(det) < 1e-14) return std::nullopt;  // ray parallel to the plane
  const double inv_det = 1.0 / det;
  const Vec3 s = ray.origin - tri.a;
  const double u = s.dot(p) * inv_det;
  if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) return std::nullopt;
  const Vec3 q = s.cross(edge1);
  const double v = ray.direction.dot(q) * inv_det;
  if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) return std::nullopt;
  const double t = edge2.dot(q) * inv_det;
  if (t <= kMinHitDistance || t >= t_max) return std::nullopt;
  return t;
}

std::optional<double> intersect(const Ray& ray, const Sphere& sphere, double t_max) {
  const Vec3 oc = ray.origin - sphere.center;
  const double half_b = oc.dot(ray.direction);
  const double c = oc.squaredNorm() - sphere.radius * sphere.radius;
  const double discriminant = half_b * half_b - c;
  if (discriminant < 0.0) return std::nullopt;
  const double root = std::sqrt(discriminant);
  double t = -half_b - root;
  if (t <= kMinHitDistance) t = -half_b + root;  // origin inside the sphere
  if (t <= kMinHitDistance || t >= t_max) return std::nullopt;
  return t;
}

}  // namespace hba::sim
