#include "hba/ba/association.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/release_memory.hpp"
#include "dist/bytes.hpp"
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

// A plane's cluster as it travels between processes (FrameCluster keeps
// its fields private): read back, the same values to the bit.
struct PackedCluster {
  std::uint32_t frame = 0;
  std::uint32_t count = 0;
  double mean[3] = {};
  double scatter[6] = {};  // xx xy xz yy yz zz
};

std::vector<PackedCluster> packed(const std::vector<FrameCluster>& clusters) {
  std::vector<PackedCluster> out(clusters.size());
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    const FrameCluster& c = clusters[k];
    const Mat3 S = c.scatter();
    out[k] = {c.frame,
              static_cast<std::uint32_t>(c.count()),
              {c.mean().x(), c.mean().y(), c.mean().z()},
              {S(0, 0), S(0, 1), S(0, 2), S(1, 1), S(1, 2), S(2, 2)}};
  }
  return out;
}

std::vector<FrameCluster> unpacked(const std::vector<PackedCluster>& clusters) {
  std::vector<FrameCluster> out;
  out.reserve(clusters.size());
  for (const PackedCluster& c : clusters) {
    PointCluster points;
    points.count = static_cast<double>(c.count);
    points.mean = Vec3(c.mean[0], c.mean[1], c.mean[2]);
    const double* v = c.scatter;
    points.scatter << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    out.emplace_back(c.frame, points);
  }
  return out;
}

// The planes of `mine` (all planes [first, first + mine.size())) that
// fall in each other member's range of `begin` (all planes, per member,
// and the total last), packed for that member; none for `self`.
std::vector<dist::Bytes> packForMembers(const std::vector<PlaneObservation>& mine, std::size_t first,
                                        const std::vector<std::size_t>& begin, std::size_t self) {
  std::vector<dist::Bytes> out(begin.size() - 1);
  for (std::size_t member = 0; member + 1 < begin.size(); ++member) {
    if (member == self) continue;
    dist::ByteWriter writer;
    const std::size_t from = std::max(first, begin[member]);
    const std::size_t to = std::min(first + mine.size(), begin[member + 1]);
    for (std::size_t p = from; p < to; ++p) writer.putVector(packed(mine[p - first].clusters));
    out[member] = writer.take();
  }
  return out;
}

void unpackInto(const dist::Bytes& bytes, std::vector<PlaneObservation>& planes) {
  dist::ByteReader reader(bytes);
  while (!reader.done()) planes.emplace_back().clusters = unpacked(reader.getVector<PackedCluster>());
}

}  // namespace

Association associateSpread(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                            const voxel::PlaneSettings& planes, double reject_ratio,
                            const dist::Group& group) {
  const auto members = static_cast<std::size_t>(group.size());
  if (members == 1) {
    Association one = associate(scans, poses, planes, reject_ratio);
    one.extraction = {};
    return one;
  }
  // This member's share of the root voxels; the shares in member order
  // are the planes of one extraction in order.
  voxel::PlaneExtraction extraction =
      voxel::extractPlanes(scans, poses, planes, static_cast<std::size_t>(group.rank()), members);
  std::vector<PlaneObservation> found(extraction.planes.size());
  for (std::size_t p = 0; p < found.size(); ++p) found[p].clusters = std::move(extraction.planes[p].clusters);
  extraction = {};
  const FrameTransforms frames(poses);
  std::vector<double> cost(found.size());
  std::vector<double> residual(found.size());
  std::vector<double> observations(found.size());
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t p) {
    cost[p] = planeCost(found[p], frames);
    residual[p] = cost[p] / found[p].pointCount();
    observations[p] = static_cast<double>(found[p].clusters.size());
  });
  // The outlier filter over every member's planes, the same everywhere:
  // each plane's residual, cost and observation count, in member order.
  std::vector<double> figures;
  figures.reserve(3 * found.size());
  for (std::size_t p = 0; p < found.size(); ++p)
    figures.insert(figures.end(), {residual[p], cost[p], observations[p]});
  std::vector<double> all_residuals, all_costs, all_observations;
  std::vector<std::size_t> found_before{0};  // planes found by earlier members
  for (const std::vector<double>& theirs : gatherPerMember(group, figures)) {
    for (std::size_t k = 0; k + 2 < theirs.size(); k += 3) {
      all_residuals.push_back(theirs[k]);
      all_costs.push_back(theirs[k + 1]);
      all_observations.push_back(theirs[k + 2]);
    }
    found_before.push_back(all_residuals.size());
  }
  const std::vector<std::size_t> best = keepBestPlanes(all_residuals, reject_ratio);
  Association out;
  out.plane_costs.reserve(best.size());
  std::vector<std::uint32_t> plane_begin{0};
  std::vector<PlaneObservation> kept;
  std::size_t first_kept = best.size();  // this member's first kept plane among all kept
  const std::size_t mine_from = found_before[static_cast<std::size_t>(group.rank())];
  const std::size_t mine_to = found_before[static_cast<std::size_t>(group.rank()) + 1];
  for (std::size_t k = 0; k < best.size(); ++k) {
    const std::size_t p = best[k];
    out.plane_costs.push_back(all_costs[p]);
    plane_begin.push_back(plane_begin.back() + static_cast<std::uint32_t>(all_observations[p]));
    if (p >= mine_from && p < mine_to) {
      first_kept = std::min(first_kept, k);
      kept.push_back(std::move(found[p - mine_from]));
    }
  }
  if (kept.empty()) first_kept = 0;
  found = {};
  // Each member then holds whole chunks of the sums: the planes move to
  // the member whose chunks hold them (mostly their own already).
  PlaneSpread spread;
  spread.group = &group;
  spread.planes = best.size();
  spread.chunk_begin = sumChunks(plane_begin, poses.size());
  // Each member's chunks start where its own kept planes do (the first
  // chunk starting there or after): they mostly stay where they are.
  std::vector<std::size_t> kept_start;  // per member, then all kept planes
  for (std::size_t m = 0; m < members; ++m) {
    kept_start.push_back(
        static_cast<std::size_t>(std::lower_bound(best.begin(), best.end(), found_before[m]) - best.begin()));
  }
  kept_start.push_back(best.size());
  const std::vector<std::size_t> chunk_start = memberChunkStarts(spread.chunk_begin, kept_start);
  std::vector<std::size_t> member_begin;  // each member's planes once moved, then all
  for (const std::size_t c : chunk_start) member_begin.push_back(spread.chunk_begin[c]);
  const auto rank = static_cast<std::size_t>(group.rank());
  spread.first_chunk = chunk_start[rank];
  spread.end_chunk = chunk_start[rank + 1];
  spread.first_plane = spread.chunk_begin[spread.first_chunk];
  // Planes of lower members come first, then this member's own (which stay
  // as they are), then higher members'.
  const std::vector<dist::Bytes> received =
      group.allToAll(packForMembers(kept, first_kept, member_begin, rank));
  std::vector<PlaneObservation> held;
  for (std::size_t m = 0; m < rank; ++m) unpackInto(received[m], held);
  for (std::size_t p = std::max(first_kept, member_begin[rank]);
       p < std::min(first_kept + kept.size(), member_begin[rank + 1]); ++p)
    held.push_back(std::move(kept[p - first_kept]));
  for (std::size_t m = rank + 1; m < members; ++m) unpackInto(received[m], held);
  kept = {};
  out.problem = PlaneProblem(std::move(held), poses.size(), std::move(spread));
  std::size_t points = 0;
  for (const PointCloud* scan : scans) points += scan->size();
  if (points >= kReleaseMemoryFrom) releaseFreedMemory();  // as associate() does
  return out;
}

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
