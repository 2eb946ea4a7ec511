#include "hba/sim/world.hpp"

#include <algorithm>
#include <cmath>

namespace hba::sim {

World::World(std::vector<Triangle> triangles, std::vector<Sphere> spheres)
    : triangles_(std::move(triangles)), spheres_(std::move(spheres)) {
  std::vector<Aabb> bounds;
  bounds.reserve(triangles_.size() + spheres_.size());
  for (const Triangle& t : triangles_) bounds.push_back(t.bounds());
  for (const Sphere& s : spheres_) bounds.push_back(s.bounds());
  bvh_ = Bvh(bounds);
}

std::optional<SurfaceHit> World::intersect(const Ray& ray, double max_distance) const {
  const auto triangle_count = static_cast<std::uint32_t>(triangles_.size());
  const auto hit = bvh_.closestHit(ray, max_distance, [&](std::uint32_t index, double t_max) {
    return index < triangle_count ? sim::intersect(ray, triangles_[index], t_max)
                                  : sim::intersect(ray, spheres_[index - triangle_count], t_max);
  });
  if (!hit) return std::nullopt;
  SurfaceHit result;
  result.distance = hit->distance;
  result.point = ray.origin + hit->distance * ray.direction;
  result.primitive = hit->primitive;
  if (hit->primitive < triangle_count) {
    const Triangle& t = triangles_[hit->primitive];
    result.normal = t.normal();
    result.reflectivity = t.reflectivity;
  } else {
    const Sphere& s = spheres_[hit->primitive - triangle_count];
    result.normal = (result.point - s.center).normalized();
    result.reflectivity = s.reflectivity;
  }
  if (result.normal.dot(ray.direction) > 0.0) result.normal = -result.normal;
  return result;
}

double World::distanceToPrimitive(std::uint32_t index, const Vec3& point) const {
  if (index < triangles_.size()) {
    // The hit lies inside the triangle, so its distance to the plane suffices.
    const Triangle& t = triangles_[index];
    return std::abs(t.normal().dot(point - t.a));
  }
  const Sphere& s = spheres_.at(index - triangles_.size());
  return std::abs((point - s.center).norm() - s.radius);
}

}  // namespace hba::sim
