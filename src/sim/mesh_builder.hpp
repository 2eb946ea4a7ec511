#pragma once
// Appends simple solids, as triangles, to a growing mesh.
#include <vector>

#include "hba/sim/primitives.hpp"

namespace hba::sim {

class MeshBuilder {
 public:
  void addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, float reflectivity);
  // Quad a-b-c-d (in order around its edge) as two triangles.
  void addQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, float reflectivity);
  // A box standing on z = base_z: footprint length x width centred on
  // `center` (x, y) and turned by `yaw`; sides and roof, no floor.
  void addBox(const Eigen::Vector2d& center, double base_z, double length, double width, double height,
              double yaw, float reflectivity);
  // A vertical prism with `sides` faces approximating a cylinder, with a top cap.
  void addPrism(const Eigen::Vector2d& center, double base_z, double radius, double height, int sides,
                float reflectivity);

  std::vector<Triangle>& triangles() { return triangles_; }

 private:
  std::vector<Triangle> triangles_;
};

}  // namespace hba::sim
