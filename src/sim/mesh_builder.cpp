#include "mesh_builder.hpp"

#include <array>
#include <cmath>

namespace hba::sim {

void MeshBuilder::addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, float reflectivity) {
  triangles_.push_back(Triangle{a, b, c, reflectivity});
}

void MeshBuilder::addQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, float reflectivity) {
  addTriangle(a, b, c, reflectivity);
  addTriangle(a, c, d, reflectivity);
}

void MeshBuilder::addBox(const Eigen::Vector2d& center, double base_z, double length, double width,
                         double height, double yaw, float reflectivity) {
  const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector2d across(-along.y(), along.x());
  std::array<Eigen::Vector2d, 4> corners{
      center + 0.5 * (length * along + width * across), center + 0.5 * (-length * along + width * across),
      center + 0.5 * (-length * along - width * across), center + 0.5 * (length * along - width * across)};
  std::array<Vec3, 4> bottom, top;
  for (int i = 0; i < 4; ++i) {
    bottom[i] = Vec3(corners[i].x(), corners[i].y(), base_z);
    top[i] = Vec3(corners[i].x(), corners[i].y(), base_z + height);
  }
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    addQuad(bottom[i], bottom[j], top[j], top[i], reflectivity);
  }
  addQuad(top[0], top[1], top[2], top[3], reflectivity);
}

void MeshBuilder::addPrism(const Eigen::Vector2d& center, double base_z, double radius, double height,
                           int sides, float reflectivity) {
  const Vec3 top_center(center.x(), center.y(), base_z + height);
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2.0 * M_PI * i / sides;
    const double a1 = 2.0 * M_PI * (i + 1) / sides;
    const Vec3 p0(center.x() + radius * std::cos(a0), center.y() + radius * std::sin(a0), base_z);
    const Vec3 p1(center.x() + radius * std::cos(a1), center.y() + radius * std::sin(a1), base_z);
    const Vec3 up(0, 0, height);
    addQuad(p0, p1, p1 + up, p0 + up, reflectivity);
    addTriangle(p0 + up, p1 + up, top_center, reflectivity);
  }
}

}  // namespace hba::sim
