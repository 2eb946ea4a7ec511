#pragma once
// The path, planar, every `spacing` metres of travel: where roadside and
// corridor pieces are placed, and which way is left there.
#include <cmath>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::sim {

struct PathSample {
  Eigen::Vector2d position;
  Eigen::Vector2d left;  // unit, to the left of the direction of travel
  double yaw = 0.0;      // heading of the sensor's x axis (rad)
};

inline std::vector<PathSample> samplePath(const std::vector<Pose>& path, double spacing) {
  std::vector<PathSample> out;
  double travelled = spacing;
  for (std::size_t k = 1; k < path.size(); ++k) {
    travelled += (path[k].t - path[k - 1].t).head<2>().norm();
    if (travelled < spacing) continue;
    travelled = 0.0;
    const Vec3 forward = path[k].R().col(0);
    const double yaw = std::atan2(forward.y(), forward.x());
    out.push_back({path[k].t.head<2>(), Eigen::Vector2d(-std::sin(yaw), std::cos(yaw)), yaw});
  }
  return out;
}

}  // namespace hba::sim
