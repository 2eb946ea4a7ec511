#include "hba/ba/plane_problem.hpp"

#include <string>

#include <tbb/parallel_for.h>

#include "hba/core/error.hpp"

namespace hba::ba {

PlaneProblem::PlaneProblem(std::vector<PlaneObservation> planes, std::size_t num_frames)
    : planes_(std::move(planes)), num_frames_(num_frames), uses_(num_frames) {
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const auto& clusters = planes_[p].clusters;
    for (std::size_t a = 0; a < clusters.size(); ++a) {
      if (clusters[a].frame >= num_frames_) {
        throw Error("plane problem: plane " + std::to_string(p) + " names frame " +
                    std::to_string(clusters[a].frame) + " of " + std::to_string(num_frames_));
      }
      // linearize() relies on this order to build only half the Hessian.
      if (a > 0 && clusters[a].frame <= clusters[a - 1].frame) {
        throw Error("plane problem: plane " + std::to_string(p) +
                    " lists its frames out of order or twice");
      }
      uses_[clusters[a].frame].emplace_back(p, a);
    }
  }
}

std::vector<double> PlaneProblem::planeCosts(const std::vector<Pose>& poses) const {
  const FrameTransforms frames(poses);
  std::vector<double> costs(planes_.size());
  // Each plane writes only its own slot: no reduction, no ordering issue.
  tbb::parallel_for(std::size_t{0}, planes_.size(),
                    [&](std::size_t p) { costs[p] = planeCost(planes_[p], frames); });
  return costs;
}

double PlaneProblem::cost(const std::vector<Pose>& poses) const {
  double total = 0.0;
  for (double c : planeCosts(poses)) total += c;  // fixed order: deterministic
  return total;
}

Linearization PlaneProblem::linearize(const std::vector<Pose>& poses) const {
  const FrameTransforms frames(poses);
  std::vector<PlaneLinearization> per_plane(planes_.size());
  tbb::parallel_for(std::size_t{0}, planes_.size(),
                    [&](std::size_t p) { per_plane[p] = linearizePlane(planes_[p], frames); });

  Linearization out;
  out.gradient.setZero(6 * num_frames_);
  out.hessian.setZero(6 * num_frames_, 6 * num_frames_);
  for (const PlaneLinearization& lin : per_plane) out.cost += lin.cost;

  // Block row i gathers, in plane order, every plane that sees frame i; only
  // the pairs of frames that share a plane are touched. Rows are disjoint, so
  // threads never write the same entry and the sums have a fixed order.
  // Clusters come in ascending frame order, so b >= a gives the blocks on and
  // right of the diagonal; the rest is their mirror image (half the work).
  tbb::parallel_for(std::size_t{0}, num_frames_, [&](std::size_t i) {
    for (const auto& [p, a] : uses_[i]) {
      const PlaneLinearization& lin = per_plane[p];
      const auto& clusters = planes_[p].clusters;
      out.gradient.segment<6>(6 * i) += lin.gradient.segment<6>(6 * a);
      out.hessian.block<6, 6>(6 * i, 6 * i) += lin.diagonal[a];
      const Eigen::Matrix<double, 6, 3> left =
          lin.Z.middleCols<6>(6 * a).transpose() * lin.weights.asDiagonal();
      for (std::size_t b = a; b < clusters.size(); ++b) {
        const std::size_t j = clusters[b].frame;
        out.hessian.block<6, 6>(6 * i, 6 * j).noalias() += left * lin.Z.middleCols<6>(6 * b);
      }
    }
  });
  out.hessian.triangularView<Eigen::StrictlyLower>() = out.hessian.transpose();
  return out;
}

}  // namespace hba::ba
