#pragma once
// Helpers of the session tests: pose comparison and how well two scans, each
// moved into the world by its pose, lie on the same surfaces.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Eigenvalues>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::sim::test {

inline bool posesNear(const Pose& a, const Pose& b, double tolerance) {
  return (a.t - b.t).norm() <= tolerance && a.q.angularDistance(b.q) <= tolerance;
}

// Median distance from the points of `b` (moved by `pose_b`) to the local
// plane of their neighbours within 1 m in `a` (moved by `pose_a`), where
// those neighbours are planar: about the range noise when both scans see the
// same surfaces at the same place.
inline double nearestNeighbourMedian(const PointCloud& a, const Pose& pose_a, const PointCloud& b,
                                     const Pose& pose_b) {
  constexpr double kCell = 1.0;
  const auto key = [](const Vec3& p) {
    const auto c = [](double v) { return static_cast<std::int64_t>(std::floor(v / kCell)) & 0x1FFFFF; };
    return (c(p.x()) << 42) | (c(p.y()) << 21) | c(p.z());
  };
  std::vector<Vec3> world_a;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  for (const Vec3f& p : a.points) {
    world_a.push_back(pose_a * p.cast<double>());
    grid[key(world_a.back())].push_back(world_a.size() - 1);
  }
  std::vector<double> distances;
  for (std::size_t i = 0; i < b.size(); i += 7) {  // a sample is plenty
    const Vec3 q = pose_b * b.points[i].cast<double>();
    std::vector<Vec3> near;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto cell = grid.find(key(q + kCell * Vec3(dx, dy, dz)));
          if (cell == grid.end()) continue;
          for (std::size_t j : cell->second) {
            if ((world_a[j] - q).norm() < kCell) near.push_back(world_a[j]);
          }
        }
      }
    }
    if (near.size() < 6) continue;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : near) mean += p;
    mean /= static_cast<double>(near.size());
    Mat3 scatter = Mat3::Zero();
    for (const Vec3& p : near) scatter += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(scatter);
    // Planar neighbourhoods only: foliage has no local plane to measure
    // against, and a single scan line (a ring on the ground) spans none.
    const Vec3 spread = solver.eigenvalues();
    if (spread(0) > 0.01 * spread(1) || spread(1) < 0.05 * spread(2)) continue;
    distances.push_back(std::abs(solver.eigenvectors().col(0).dot(q - mean)));
  }
  if (distances.size() < 100) return 1e9;  // too little overlap to tell
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2];
}

}  // namespace hba::sim::test
