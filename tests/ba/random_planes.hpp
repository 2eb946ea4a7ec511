#pragma once
// Random plane observations with known raw points, for derivative checks.
#include <random>
#include <vector>

#include "hba/ba/plane_cost.hpp"
#include "hba/core/lie.hpp"

namespace hba::test {

struct RandomPlane {
  ba::PlaneObservation observation;
  std::vector<std::vector<Vec3>> sensor_points;  // per cluster, in its frame
};

inline Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

inline std::vector<Pose> randomPoses(std::mt19937& rng, int count, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Pose> poses;
  for (int i = 0; i < count; ++i) {
    poses.emplace_back(so3Exp(u(rng) * 2.0 * randomUnit(rng)), Vec3(spread * Vec3(u(rng), u(rng), u(rng))));
  }
  return poses;
}

// A noisy planar patch (thickness `sigma`) seen by `frames`.
inline RandomPlane randomPlane(std::mt19937& rng, const std::vector<Pose>& poses,
                               const std::vector<std::uint32_t>& frames, int points_per_frame, double sigma) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::normal_distribution<double> g(0.0, sigma);
  const Vec3 normal = randomUnit(rng);
  const Vec3 e1 = normal.unitOrthogonal();
  const Vec3 e2 = normal.cross(e1);
  const Vec3 center = 4.0 * Vec3(u(rng), u(rng), u(rng));
  RandomPlane plane;
  for (std::uint32_t f : frames) {
    ba::PointCluster cluster;
    std::vector<Vec3> points;
    for (int k = 0; k < points_per_frame; ++k) {
      const Vec3 q = center + u(rng) * e1 + u(rng) * e2 + g(rng) * normal;
      points.push_back(poses[f].inverse() * q);
      cluster.add(points.back());
    }
    plane.observation.clusters.emplace_back(f, cluster);
    plane.sensor_points.push_back(std::move(points));
  }
  return plane;
}

}  // namespace hba::test
