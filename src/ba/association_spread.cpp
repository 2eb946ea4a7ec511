// associateSpread: one association made by the members of a process group
// together, each ending with whole chunks of the planes (plane_spread.hpp).
#include <algorithm>
#include <cstdint>

#include <tbb/parallel_for.h>

#include "core/release_memory.hpp"
#include "dist/bytes.hpp"
#include "hba/ba/association.hpp"

namespace hba::ba {
namespace {

// From this many points an association returns its freed memory (as
// associate() does).
constexpr std::size_t kReleaseMemoryFrom = std::size_t{4} << 20;

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

// Each member's planes, as every member sees them: in member order, each
// plane's residual (the outlier filter's), cost and observation count.
struct AllPlanes {
  std::vector<double> residual, cost, observations;
  std::vector<std::size_t> found_before;  // per member, then all
};

AllPlanes gatherPlanes(const dist::Group& group, const std::vector<PlaneObservation>& found,
                       const std::vector<Pose>& poses) {
  const FrameTransforms frames(poses);
  std::vector<double> figures(3 * found.size());
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t p) {
    const double cost = planeCost(found[p], frames);
    figures[3 * p] = cost / found[p].pointCount();
    figures[3 * p + 1] = cost;
    figures[3 * p + 2] = static_cast<double>(found[p].clusters.size());
  });
  AllPlanes all;
  all.found_before.push_back(0);
  for (const std::vector<double>& theirs : gatherPerMember(group, figures)) {
    for (std::size_t k = 0; k + 2 < theirs.size(); k += 3) {
      all.residual.push_back(theirs[k]);
      all.cost.push_back(theirs[k + 1]);
      all.observations.push_back(theirs[k + 2]);
    }
    all.found_before.push_back(all.residual.size());
  }
  return all;
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

// The chunks of the kept planes (`kept_begin`: observations before each,
// then all) and each member's: those starting where its own kept planes
// do (`kept_start`), so that planes mostly stay where they were found.
PlaneSpread chunksOf(const dist::Group& group, const std::vector<std::uint32_t>& kept_begin,
                     const std::vector<std::size_t>& kept_start, std::size_t frames,
                     std::vector<std::size_t>& member_begin) {
  PlaneSpread spread;
  spread.group = &group;
  spread.chunk_begin = sumChunks(kept_begin, frames);
  const std::vector<std::size_t> chunk_start = memberChunkStarts(spread.chunk_begin, kept_start);
  member_begin.clear();
  for (const std::size_t c : chunk_start) member_begin.push_back(spread.chunk_begin[c]);
  const auto rank = static_cast<std::size_t>(group.rank());
  spread.first_chunk = chunk_start[rank];
  spread.end_chunk = chunk_start[rank + 1];
  return spread;
}

// This member's planes once each member holds its chunks' (`member_begin`):
// lower members' first, then its own `kept` (all planes [first, first +
// kept.size())) that stay, then higher members'. A collective.
std::vector<PlaneObservation> movedToChunks(const dist::Group& group, std::vector<PlaneObservation> kept,
                                            std::size_t first, const std::vector<std::size_t>& member_begin) {
  const auto rank = static_cast<std::size_t>(group.rank());
  const std::vector<dist::Bytes> received = group.allToAll(packForMembers(kept, first, member_begin, rank));
  std::vector<PlaneObservation> held;
  for (std::size_t m = 0; m < rank; ++m) unpackInto(received[m], held);
  const std::size_t end = std::min(first + kept.size(), member_begin[rank + 1]);
  for (std::size_t p = std::max(first, member_begin[rank]); p < end; ++p)
    held.push_back(std::move(kept[p - first]));
  for (std::size_t m = rank + 1; m < received.size(); ++m) unpackInto(received[m], held);
  return held;
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
  const auto rank = static_cast<std::size_t>(group.rank());
  std::vector<PlaneObservation> found;
  for (voxel::PlaneFeature& feature : voxel::extractPlanes(scans, poses, planes, rank, members).planes)
    found.emplace_back().clusters = std::move(feature.clusters);
  // The outlier filter over every member's planes, the same everywhere.
  const AllPlanes all = gatherPlanes(group, found, poses);
  const std::vector<std::size_t> best = keepBestPlanes(all.residual, reject_ratio);
  Association out;
  out.plane_costs.reserve(best.size());
  std::vector<std::uint32_t> kept_begin{0};  // observations before each kept plane
  for (const std::size_t p : best) {
    out.plane_costs.push_back(all.cost[p]);
    kept_begin.push_back(kept_begin.back() + static_cast<std::uint32_t>(all.observations[p]));
  }
  // Where each member's kept planes start among all kept, and its own.
  std::vector<std::size_t> kept_start;
  for (const std::size_t before : all.found_before) {
    kept_start.push_back(
        static_cast<std::size_t>(std::lower_bound(best.begin(), best.end(), before) - best.begin()));
  }
  std::vector<PlaneObservation> kept;
  for (std::size_t k = kept_start[rank]; k < kept_start[rank + 1]; ++k)
    kept.push_back(std::move(found[best[k] - all.found_before[rank]]));
  found = {};
  std::vector<std::size_t> member_begin;
  PlaneSpread spread = chunksOf(group, kept_begin, kept_start, poses.size(), member_begin);
  out.problem = PlaneProblem(movedToChunks(group, std::move(kept), kept_start[rank], member_begin),
                             poses.size(), std::move(spread));
  std::size_t points = 0;
  for (const PointCloud* scan : scans) points += scan->size();
  if (points >= kReleaseMemoryFrom) releaseFreedMemory();
  return out;
}

}  // namespace hba::ba
