#include "hba/ba/plane_problem.hpp"

#include <algorithm>
#include <string>

#include <tbb/parallel_for.h>

#include "hba/core/error.hpp"

namespace hba::ba {

PlaneProblem::PlaneProblem(std::vector<PlaneObservation> planes, std::size_t num_frames)
    : planes_(std::move(planes)), num_frames_(num_frames) {
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const auto& clusters = planes_[p].clusters;
    for (std::size_t a = 0; a < clusters.size(); ++a) {
      if (clusters[a].frame >= num_frames_) {
        throw Error("plane problem: plane " + std::to_string(p) + " names frame " +
                    std::to_string(clusters[a].frame) + " of " + std::to_string(num_frames_));
      }
      // linearize() relies on this order to build only half the Hessian.
      if (a > 0 && clusters[a].frame <= clusters[a - 1].frame) {
        throw Error("plane problem: plane " + std::to_string(p) + " lists its frames out of order or twice");
      }
    }
  }
}

PlaneProblem::PlaneProblem(std::vector<PlaneObservation> planes, std::size_t num_frames, PlaneSpread spread)
    : PlaneProblem(std::move(planes), num_frames) {
  spread_ = std::move(spread);
}

std::vector<double> PlaneProblem::planeCosts(const std::vector<Pose>& poses) const {
  const FrameTransforms frames(poses);
  std::vector<double> costs(planes_.size());
  // Each plane writes only its own slot: no reduction, no ordering issue.
  tbb::parallel_for(std::size_t{0}, planes_.size(),
                    [&](std::size_t p) { costs[p] = planeCost(planes_[p], frames); });
  return costs;
}

double PlaneProblem::total(const std::vector<double>& plane_costs) {
  double sum = 0.0;
  for (double c : plane_costs) sum += c;  // fixed order: deterministic
  return sum;
}

std::vector<double> PlaneProblem::allPlaneCosts(const std::vector<Pose>& poses) const {
  if (!spread_.spread()) return planeCosts(poses);
  return gatherInOrder(*spread_.group, planeCosts(poses));
}

double PlaneProblem::cost(const std::vector<Pose>& poses) const { return total(allPlaneCosts(poses)); }

namespace {

// Planes are linearized and summed in fixed chunks, each into its own dense
// gradient and Hessian, and the chunks are added in order: the same sums
// for any thread count, no per-plane storage, and each chunk's Hessian stays
// in cache (a window's is 29 kB). Chunks are bounded by their memory (64 MB
// in all) and hold at least 16 planes, and at least unknowns^2 / 1024: a
// chunk's Hessian is cleared and added once, its planes' blocks many times
// (53-scan windows in 64 chunks spent a fifth of nclt's run clearing pages).
std::vector<std::size_t> chunkBegins(std::size_t planes, std::size_t unknowns) {
  const std::size_t bytes = unknowns * unknowns * sizeof(double) + 1;
  const std::size_t by_memory = (std::size_t{64} << 20) / bytes;
  const std::size_t least_planes = std::max<std::size_t>(16, unknowns * unknowns / 1024);
  const std::size_t chunks = std::clamp<std::size_t>(std::min(by_memory, planes / least_planes), 1, 64);
  std::vector<std::size_t> begin;
  for (std::size_t c = 0; c <= chunks; ++c) begin.push_back(planes * c / chunks);
  return begin;
}

// Adds one plane's cost, gradient and the blocks on and right of the
// diagonal of its Hessian (clusters ascend by frame).
void addPlane(const PlaneObservation& plane, const PlaneTerms& terms, Linearization& out) {
  out.cost += terms.cost;
  const auto& clusters = plane.clusters;
  for (std::size_t a = 0; a < clusters.size(); ++a) {
    const auto i = static_cast<Eigen::Index>(6 * clusters[a].frame);
    out.gradient.segment<6>(i) += terms.gradient[a];
    out.hessian.block<6, 6>(i, i) += terms.diagonal[a];
    const Eigen::Matrix<double, 6, 3> left = terms.z[a].transpose() * terms.weights.asDiagonal();
    for (std::size_t b = a; b < clusters.size(); ++b) {
      const auto j = static_cast<Eigen::Index>(6 * clusters[b].frame);
      out.hessian.block<6, 6>(i, j).noalias() += left * terms.z[b];
    }
  }
}

}  // namespace

Linearization PlaneProblem::linearize(const std::vector<Pose>& poses) const {
  const FrameTransforms frames(poses);
  const auto n = static_cast<Eigen::Index>(6 * num_frames_);
  const std::vector<std::size_t> begin = chunkBegins(planes_.size(), static_cast<std::size_t>(n));
  const std::size_t chunks = begin.size() - 1;

  std::vector<Linearization> partial(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    Linearization& part = partial[c];
    part.gradient.setZero(n);
    part.hessian.setZero(n, n);
    thread_local PlaneTerms terms;
    for (std::size_t p = begin[c]; p < begin[c + 1]; ++p) {
      planeTerms(planes_[p], frames, terms);
      addPlane(planes_[p], terms, part);
    }
  });

  Linearization out = std::move(partial.front());
  for (std::size_t c = 1; c < chunks; ++c) {
    out.cost += partial[c].cost;
    out.gradient += partial[c].gradient;
    out.hessian += partial[c].hessian;
    partial[c] = Linearization{};  // free as we go: a global BA's are large
  }
  out.hessian.triangularView<Eigen::StrictlyLower>() = out.hessian.transpose();
  return out;
}

}  // namespace hba::ba
