#include "hba/ba/offset_noise.hpp"

#include <Eigen/Eigenvalues>

#include "hba/ba/plane_cost.hpp"

namespace hba::ba {

FrameOffsets frameOffsets(const PlaneProblem& problem, const std::vector<Pose>& poses) {
  const FrameTransforms frames(poses);
  FrameOffsets out;
  std::vector<Vec3> centroids;
  for (const PlaneObservation& plane : problem.planes()) {
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(planeScatter(plane, frames));
    const Vec3 normal = eigen.eigenvectors().col(0);  // smallest eigenvalue first
    centroids.clear();
    Vec3 weighted = Vec3::Zero();
    double points = 0.0;
    for (const FrameCluster& cluster : plane.clusters) {
      centroids.push_back(frames.R[cluster.frame] * cluster.mean() + frames.t[cluster.frame]);
      weighted += cluster.count() * centroids.back();
      points += cluster.count();
    }
    if (!(points > 0.0)) continue;
    const Vec3 centre = weighted / points;
    for (std::size_t a = 0; a < centroids.size(); ++a) {
      const double offset = normal.dot(centroids[a] - centre);
      out.cost += plane.clusters[a].count() * offset * offset;
    }
    out.pairs += static_cast<double>(centroids.size());
    out.planes += 1.0;
  }
  return out;
}

double offsetNoiseGain(const FrameOffsets& offsets, std::size_t frames) {
  if (frames < 2) return 0.0;
  const double dof = 6.0 * static_cast<double>(frames - 1);
  const double remaining = offsets.pairs - offsets.planes - dof;
  if (!(remaining > 0.0)) return 0.0;
  return dof * offsets.cost / remaining;
}

}  // namespace hba::ba
