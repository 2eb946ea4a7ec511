#include "hba/ba/association.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/release_memory.hpp"
#include "hba/ba/plane_problem.hpp"

namespace hba::ba {

std::vector<std::size_t> keepBestPlanes(const std::vector<double>& residual, double reject_ratio) {
  std::vector<std::size_t> order(residual.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto drop = static_cast<std::size_t>(
      std::floor(std::clamp(reject_ratio, 0.0, 1.0) * static_cast<double>(residual.size())));
  if (drop == 0) return order;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return residual[a] < residual[b]; });
  order.resize(order.size() - drop);
  std::sort(order.begin(), order.end());
  return order;
}

namespace {

// From this many points an association returns its freed memory.
constexpr std::size_t kReleaseMemoryFrom = std::size_t{4} << 20;

// The plane problem of the planes found at `poses`, the worst dropped.
Association associationOf(voxel::PlaneExtraction extraction, const std::vector<Pose>& poses,
                          double reject_ratio) {
  std::vector<voxel::PlaneFeature>& features = extraction.planes;
  std::vector<PlaneObservation> observations(features.size());
  for (std::size_t p = 0; p < features.size(); ++p)
    observations[p].clusters = std::move(features[p].clusters);

  // Outlier filter on the mean squared distance (not the sum), so that large
  // planes are not dropped merely for having many points.
  const FrameTransforms frames(poses);
  std::vector<double> cost(observations.size());
  std::vector<double> residual(observations.size());
  tbb::parallel_for(std::size_t{0}, observations.size(), [&](std::size_t p) {
    cost[p] = planeCost(observations[p], frames);
    residual[p] = cost[p] / observations[p].pointCount();
  });
  Association out;
  std::vector<PlaneObservation> kept;
  const std::vector<std::size_t> best = keepBestPlanes(residual, reject_ratio);
  out.extraction.planes.reserve(best.size());
  out.plane_costs.reserve(best.size());
  kept.reserve(best.size());
  for (std::size_t p : best) {
    out.extraction.planes.push_back(std::move(features[p]));
    out.plane_costs.push_back(cost[p]);
    kept.push_back(std::move(observations[p]));
  }
  out.extraction.point_ids = std::move(extraction.point_ids);
  out.extraction.first_id = std::move(extraction.first_id);
  out.problem = PlaneProblem(std::move(kept), poses.size());
  return out;
}

}  // namespace

double Association::cost() const { return PlaneProblem::total(plane_costs); }

Association associate(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                      const voxel::PlaneSettings& planes, double reject_ratio) {
  Association out = associationOf(voxel::extractPlanes(scans, poses, planes), poses, reject_ratio);
  // A refinement block's extraction frees hundreds of MB in small pieces
  // (octree splits, features, clusters) that the allocator would keep; the
  // next stage's peak would stack on them. Windows (a few 100 000 points,
  // many at once on the threads) leave little and keep the allocator's
  // caches.
  std::size_t points = 0;
  for (const PointCloud* scan : scans) points += scan->size();
  if (points >= kReleaseMemoryFrom) releaseFreedMemory();
  return out;
}

std::pair<Association, Association> associateAtTwoVoxels(const std::vector<const PointCloud*>& scans,
                                                         const std::vector<Pose>& poses,
                                                         const voxel::PlaneSettings& planes,
                                                         double fine_voxel, double reject_ratio) {
  auto [coarse, fine] = voxel::extractPlanesAtTwoVoxels(scans, poses, planes, fine_voxel);
  return {associationOf(std::move(coarse), poses, reject_ratio),
          associationOf(std::move(fine), poses, reject_ratio)};
}

}  // namespace hba::ba
