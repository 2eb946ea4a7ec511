#include "hba/ba/association.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "hba/ba/plane_problem.hpp"
#include "hba/core/release_memory.hpp"
#include "hba/core/shifted_moments.hpp"

namespace hba::ba {
namespace {

// Mean and scatter of one run of points, in one pass of sums relative to
// its first point (the points lie in one voxel: no cancellation), made
// exactly symmetric.
PointCluster clusterOf(const PointCloud& scan, const voxel::PointRef* begin, const voxel::PointRef* end) {
  ShiftedMoments moments(scan.points[begin->index].cast<double>());
  for (const voxel::PointRef* r = begin; r != end; ++r) moments.add(scan.points[r->index].cast<double>());
  PointCluster cluster;
  cluster.count = static_cast<double>(end - begin);
  const Vec3 offset = moments.offsetSum() / cluster.count;
  cluster.mean = moments.origin() + offset;
  cluster.scatter = moments.outerSum() - cluster.count * offset * offset.transpose();
  cluster.scatter = 0.5 * (cluster.scatter + cluster.scatter.transpose()).eval();
  return cluster;
}

PlaneObservation observationOf(const voxel::PlaneFeature& feature,
                               const std::vector<const PointCloud*>& scans) {
  PlaneObservation obs;
  const auto& refs = feature.points;  // sorted by frame: one run per frame
  // Exact size: planes of a global map hold millions of clusters, and a
  // growing vector's slack would double their memory.
  std::size_t runs = refs.empty() ? 0 : 1;
  for (std::size_t k = 1; k < refs.size(); ++k) runs += refs[k].frame != refs[k - 1].frame;
  obs.clusters.reserve(runs);
  std::size_t start = 0;
  while (start < refs.size()) {
    std::size_t stop = start;
    while (stop < refs.size() && refs[stop].frame == refs[start].frame) ++stop;
    const std::uint32_t frame = refs[start].frame;
    obs.clusters.push_back({frame, clusterOf(*scans[frame], refs.data() + start, refs.data() + stop)});
    start = stop;
  }
  return obs;
}

}  // namespace

std::vector<PlaneObservation> buildObservations(const std::vector<voxel::PlaneFeature>& features,
                                                const std::vector<const PointCloud*>& scans) {
  std::vector<PlaneObservation> out(features.size());
  tbb::parallel_for(std::size_t{0}, features.size(),
                    [&](std::size_t p) { out[p] = observationOf(features[p], scans); });
  return out;
}

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

// The plane problem of `features` found at `poses`, the worst planes dropped.
Association associationOf(std::vector<voxel::PlaneFeature> features,
                          const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                          double reject_ratio) {
  std::vector<PlaneObservation> observations = buildObservations(features, scans);

  // Outlier filter on the mean squared distance (not the sum), so that large
  // planes are not dropped merely for having many points.
  const FrameTransforms frames(poses);
  std::vector<double> residual(observations.size());
  tbb::parallel_for(std::size_t{0}, observations.size(), [&](std::size_t p) {
    residual[p] = planeCost(observations[p], frames) / observations[p].pointCount();
  });
  Association out;
  std::vector<PlaneObservation> kept;
  for (std::size_t p : keepBestPlanes(residual, reject_ratio)) {
    out.features.push_back(std::move(features[p]));
    kept.push_back(std::move(observations[p]));
  }
  out.problem = PlaneProblem(std::move(kept), poses.size());
  return out;
}

}  // namespace

Association associate(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                      const voxel::PlaneSettings& planes, double reject_ratio) {
  Association out = associationOf(voxel::extractPlanes(scans, poses, planes), scans, poses, reject_ratio);
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
  return {associationOf(std::move(coarse), scans, poses, reject_ratio),
          associationOf(std::move(fine), scans, poses, reject_ratio)};
}

}  // namespace hba::ba
