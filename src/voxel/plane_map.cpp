#include "hba/voxel/plane_map.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cell_assignment.hpp"
#include "core/shifted_moments.hpp"
#include "core/symmetric_eigenvalues.hpp"
#include "hba/core/error.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

// Window points in the world, less `origin`, addressed by a global id
// (scans in order, points in order), so that ids in a voxel are sorted by
// (frame, index). Positions are floats: they are near the origin, which is
// near the scans (a float 20 km out is 2 mm coarse; here it is 8 um).
struct WorldPoints {
  std::vector<Vec3f> position;       // world minus origin
  std::vector<std::uint32_t> first;  // first global id of each scan, and the total
  Vec3 origin = Vec3::Zero();
  std::vector<Mat3> R;  // each scan's rotation
  std::vector<Vec3> t;  // and translation less the origin
};

// The origin: the scans' mean position on a grid of 64 m, a multiple of
// every power-of-two voxel up to 64 m, so that the voxels stay where they
// would be without it, and the same for any voxel size.
Vec3 originOf(const std::vector<Pose>& poses) {
  constexpr double kGrid = 64.0;
  Vec3 mean = Vec3::Zero();
  for (const Pose& pose : poses) mean += pose.t / static_cast<double>(poses.size());
  return kGrid * (mean / kGrid).array().round().matrix();
}

// `with_points` false: the frames and offsets only, no point placed.
WorldPoints placeInWorld(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                         bool with_points = true) {
  std::size_t total = 0;
  for (const PointCloud* scan : scans) total += scan->size();
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("plane extraction: more than 2^32 points in one window");
  }
  WorldPoints world;
  world.first.push_back(0);
  for (const PointCloud* scan : scans)
    world.first.push_back(world.first.back() + static_cast<std::uint32_t>(scan->size()));
  if (!poses.empty()) world.origin = originOf(poses);
  for (const Pose& pose : poses) {
    world.R.push_back(pose.R());
    world.t.push_back(pose.t - world.origin);
  }
  if (!with_points) return world;
  world.position.resize(total);
  tbb::parallel_for(std::size_t{0}, scans.size(), [&](std::size_t f) {
    const Mat3& R = world.R[f];
    const Vec3& t = world.t[f];
    const auto& points = scans[f]->points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      world.position[world.first[f] + i] = (R * points[i].cast<double>() + t).cast<float>();
    }
  });
  return world;
}

// A run of point ids, ascending, inside one cell.
struct IdSpan {
  std::uint32_t* begin;
  std::uint32_t* end;
  std::size_t size() const { return static_cast<std::size_t>(end - begin); }
};

// Eigenvalues (ascending) of the covariance of `n` points from their sums
// relative to the first point: a cell is a few metres wide, so the shifted
// sums lose nothing to cancellation.
Vec3 covarianceEigenvalues(const ShiftedMoments& moments, std::size_t count) {
  const double n = static_cast<double>(count);
  const Vec3 mean = moments.offsetSum() / n;
  const Mat3 cov = moments.outerSum() / n - mean * mean.transpose();
  return symmetricEigenvalues(cov);
}

ShiftedMoments momentsOf(const WorldPoints& world, IdSpan ids) {
  ShiftedMoments moments(world.position[*ids.begin].cast<double>());
  for (const std::uint32_t* id = ids.begin; id != ids.end; ++id) {
    moments.add(world.position[*id].cast<double>());
  }
  return moments;
}

// The scan of the first id of `ids`, and the end of its run of ids: spans
// ascend, so a scan's ids come in one run (no per-point frame is kept: a
// refinement block holds 20 M points).
struct FrameRun {
  std::uint32_t frame;
  const std::uint32_t* end;
};
FrameRun frameRunAt(const WorldPoints& world, const std::uint32_t* begin, const std::uint32_t* end) {
  const auto frame = static_cast<std::uint32_t>(
      std::upper_bound(world.first.begin(), world.first.end(), *begin) - world.first.begin() - 1);
  const std::uint32_t stop = world.first[frame + 1];
  return {frame, std::lower_bound(begin, end, stop)};
}

// Whether `ids` hold points of at least `wanted` frames: counts runs only
// until it knows (a refinement's plane may span hundreds of frames, each a
// binary search).
bool seenByFrames(const WorldPoints& world, IdSpan ids, int wanted) {
  int frames = 0;
  for (const std::uint32_t* id = ids.begin; id != ids.end && frames < wanted;
       id = frameRunAt(world, id, ids.end).end) {
    ++frames;
  }
  return frames >= wanted;
}

// Room for reordering the largest cell during a split.
struct SplitScratch {
  std::vector<std::uint32_t> ids;
  std::vector<std::uint8_t> octant;
  void reserve(std::size_t n) {
    if (ids.size() < n) {
      ids.resize(n);
      octant.resize(n);
    }
  }
};

class OctreeSplitter {
 public:
  // `ids`: the start of the id array the visited spans lie in.
  OctreeSplitter(const WorldPoints& world, const PlaneSettings& settings, const std::uint32_t* ids)
      : world_(world), settings_(settings), ids_(ids) {}

  // Tests the cell [corner, corner + edge)^3 holding `ids` (whose sums are
  // `moments`, when known); appends its planes. Splitting reorders `ids` in
  // place (stable, so each octant stays ascending); `scratch` must hold at
  // least ids.size() entries.
  void visit(IdSpan ids, const ShiftedMoments* moments, const Vec3& corner, double edge, int depth,
             SplitScratch& scratch, std::vector<PlaneFeature>& out) const {
    if (static_cast<int>(ids.size()) < settings_.min_points) return;
    const Vec3 eigenvalues = moments ? covarianceEigenvalues(*moments, ids.size())
                                     : covarianceEigenvalues(momentsOf(world_, ids), ids.size());
    if (passesPlaneTest(eigenvalues, settings_)) {
      if (seenByFrames(world_, ids, settings_.min_frames)) out.push_back(toFeature(ids, depth));
      return;
    }
    if (depth >= settings_.max_depth) return;
    const double half = 0.5 * edge;
    const Vec3 center = corner + Vec3::Constant(half);
    // One pass over the points: each one's octant (kept for the reordering)
    // and each octant's sums, taken in id order from its first point, as
    // the octant would take them itself.
    std::array<std::optional<ShiftedMoments>, 8> octants;
    std::array<std::size_t, 9> start{};
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const Vec3f& p = world_.position[ids.begin[k]];
      const int o =
          (p.x() >= center.x() ? 1 : 0) | (p.y() >= center.y() ? 2 : 0) | (p.z() >= center.z() ? 4 : 0);
      scratch.octant[k] = static_cast<std::uint8_t>(o);
      ++start[o + 1];
      const Vec3 q = p.cast<double>();
      if (!octants[o]) octants[o].emplace(q);
      octants[o]->add(q);
    }
    for (int o = 0; o < 8; ++o) start[o + 1] += start[o];
    std::array<std::size_t, 8> fill{};
    std::copy(start.begin(), start.end() - 1, fill.begin());
    for (std::size_t k = 0; k < ids.size(); ++k) scratch.ids[fill[scratch.octant[k]]++] = ids.begin[k];
    std::copy(scratch.ids.begin(), scratch.ids.begin() + static_cast<long>(ids.size()), ids.begin);
    for (int o = 0; o < 8; ++o) {
      const Vec3 child_corner = corner + half * Vec3((o & 1) ? 1 : 0, (o & 2) ? 1 : 0, (o & 4) ? 1 : 0);
      const ShiftedMoments* known = octants[o] ? &*octants[o] : nullptr;
      visit({ids.begin + start[o], ids.begin + start[o + 1]}, known, child_corner, half, depth + 1, scratch,
            out);
    }
  }

 private:
  // The plane of a leaf: each frame's points (a run of ids) summed where
  // they are, then taken into the frame's own coordinates (q = R p + t, so
  // p = R^T (q - t) and the scatter turns with R^T).
  PlaneFeature toFeature(IdSpan ids, int depth) const {
    PlaneFeature feature;
    feature.depth = depth;
    feature.first_point = static_cast<std::uint32_t>(ids.begin - ids_);
    feature.end_point = static_cast<std::uint32_t>(ids.end - ids_);
    // Gathered in a reused buffer and then stored at their exact count: a
    // refinement block's millions of planes would otherwise keep the slack
    // of a growing vector each (70 MB at 1000 frames) and reallocate as
    // they grow.
    thread_local std::vector<FrameCluster> clusters;
    clusters.clear();
    for (const std::uint32_t* run = ids.begin; run != ids.end;) {
      const auto [f, run_end] = frameRunAt(world_, run, ids.end);
      ShiftedMoments moments(world_.position[*run].cast<double>());
      for (const std::uint32_t* id = run; id != run_end; ++id)
        moments.add(world_.position[*id].cast<double>());
      PointCluster cluster;
      cluster.count = static_cast<double>(run_end - run);
      const Vec3 offset = moments.offsetSum() / cluster.count;
      const Mat3& R = world_.R[f];
      cluster.mean = R.transpose() * (moments.origin() + offset - world_.t[f]);
      const Mat3 scatter = moments.outerSum() - cluster.count * offset * offset.transpose();
      cluster.scatter = R.transpose() * scatter * R;
      cluster.scatter = 0.5 * (cluster.scatter + cluster.scatter.transpose()).eval();
      clusters.emplace_back(f, cluster);
      run = run_end;
    }
    feature.clusters.assign(clusters.begin(), clusters.end());
    return feature;
  }

  const WorldPoints& world_;
  const PlaneSettings& settings_;
  const std::uint32_t* ids_;
};

void validate(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
              const PlaneSettings& settings) {
  if (scans.size() != poses.size()) {
    throw Error("plane extraction: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(poses.size()) + " poses");
  }
  for (const PointCloud* scan : scans) {
    if (scan == nullptr) throw Error("plane extraction: null scan");
  }
  if (!(settings.voxel_size > 0.0) || !(settings.eigen_ratio > 0.0) || settings.max_depth < 0 ||
      settings.min_points < 3) {
    throw Error(
        "plane extraction: invalid settings (need voxel_size > 0, eigen_ratio > 0, "
        "max_depth >= 0, min_points >= 3)");
  }
}

}  // namespace

bool passesPlaneTest(const Vec3& eigenvalues, const PlaneSettings& settings) {
  const double l1 = std::max(eigenvalues(0), 0.0);
  const double l2 = eigenvalues(1);
  const double l3 = eigenvalues(2);
  if (!(l3 > 0.0)) return false;  // all points coincide
  return l1 < settings.eigen_ratio * l3 && l1 < settings.line_ratio * l2;
}

namespace {

// Plane voxels (metres) gather dozens to thousands of points each: a hash
// table sized for one cell in four points would be mostly empty (hundreds of
// MB for a refinement block).
constexpr std::size_t kPointsPerPlaneVoxel = 64;

// The planes of the root voxels `cells` (of settings.voxel_size) of `world`.
PlaneExtraction planesOfCells(const WorldPoints& world, CellAssignment cells, const PlaneSettings& settings) {
  // Root voxels, their ids ascending (counting sort by cell).
  CellMembers members = membersOf(cells);
  std::vector<VoxelKey> keys(cells.cells());
  for (std::size_t c = 0; c < keys.size(); ++c) {
    keys[c] = VoxelKey::of(world.position[cells.first_point_of_cell[c]].cast<double>(), settings.voxel_size);
  }
  cells = {};  // 4 bytes a point, while the planes' clusters grow

  // Visit voxels in key order so the output never depends on the hash.
  std::vector<std::size_t> order(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });

  const OctreeSplitter splitter(world, settings, members.ids.data());
  std::vector<std::vector<PlaneFeature>> per_voxel(order.size());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, order.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        SplitScratch scratch;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const std::size_t cell = order[i];
          const VoxelKey& key = keys[cell];
          const Vec3 corner =
              settings.voxel_size *
              Vec3(static_cast<double>(key.x), static_cast<double>(key.y), static_cast<double>(key.z));
          const IdSpan ids{members.ids.data() + members.begin[cell],
                           members.ids.data() + members.begin[cell + 1]};
          scratch.reserve(ids.size());
          splitter.visit(ids, nullptr, corner, settings.voxel_size, 0, scratch, per_voxel[i]);
        }
      });

  PlaneExtraction out;
  std::size_t count = 0;
  for (const auto& found : per_voxel) count += found.size();
  out.planes.reserve(count);
  for (auto& found : per_voxel) {
    for (auto& plane : found) out.planes.push_back(std::move(plane));
  }
  out.point_ids = std::move(members.ids);
  out.first_id = world.first;
  return out;
}

// A point of scan `f` in the world, as placeInWorld puts it.
Vec3f placed(const WorldPoints& frames, const PointCloud& scan, std::size_t f, std::size_t i) {
  return (frames.R[f] * scan.points[i].cast<double>() + frames.t[f]).cast<float>();
}

// The lowest x index of each share but the first, from a sample of the
// points (every 64th: the same in every process, and a few hundred
// thousand at most sorted), so that the shares hold about equal points.
std::vector<std::int64_t> shareBounds(const std::vector<const PointCloud*>& scans, const WorldPoints& frames,
                                      const KeyOf& keyOf, std::size_t shares) {
  constexpr std::size_t kSampleStride = 64;
  std::vector<std::int64_t> sample;
  for (std::size_t f = 0; f < scans.size(); ++f) {
    // Every 64th point of all the scans in order.
    const std::size_t first = frames.first[f];
    for (std::size_t id = (first + kSampleStride - 1) / kSampleStride * kSampleStride;
         id < frames.first[f + 1]; id += kSampleStride) {
      sample.push_back(keyOf.x(placed(frames, *scans[f], f, id - first)));
    }
  }
  std::sort(sample.begin(), sample.end());
  std::vector<std::int64_t> bounds;
  for (std::size_t k = 1; k < shares; ++k)
    bounds.push_back(sample.empty() ? 0 : sample[sample.size() * k / shares]);
  return bounds;
}

// The points of `scans` whose root voxel's x index is in [low, high), in
// the world as placeInWorld puts them, numbered as in `all` (every point:
// only its offsets and frames are read) through `ids`.
WorldPoints placeShareInWorld(const std::vector<const PointCloud*>& scans, const WorldPoints& all,
                              const KeyOf& keyOf, std::int64_t low, std::int64_t high,
                              std::vector<std::uint32_t>& ids) {
  // Which points are the share's (a byte a point), then only those placed
  // again where they go.
  std::vector<std::uint8_t> inside(all.first.back());
  const std::size_t frames = scans.size();
  std::vector<std::uint32_t> count(frames, 0);
  tbb::parallel_for(std::size_t{0}, frames, [&](std::size_t f) {
    for (std::size_t i = 0; i < scans[f]->size(); ++i) {
      const std::int64_t x = keyOf.x(placed(all, *scans[f], f, i));
      inside[all.first[f] + i] = x >= low && x < high;
      count[f] += inside[all.first[f] + i];
    }
  });
  WorldPoints world;
  world.origin = all.origin;
  world.R = all.R;
  world.t = all.t;
  world.first.push_back(0);
  for (std::size_t f = 0; f < frames; ++f) world.first.push_back(world.first.back() + count[f]);
  world.position.resize(world.first.back());
  ids.resize(world.first.back());
  tbb::parallel_for(std::size_t{0}, frames, [&](std::size_t f) {
    std::uint32_t k = world.first[f];
    for (std::size_t i = 0; i < scans[f]->size(); ++i) {
      if (!inside[all.first[f] + i]) continue;
      world.position[k] = placed(all, *scans[f], f, i);
      ids[k++] = all.first[f] + static_cast<std::uint32_t>(i);
    }
  });
  return world;
}

}  // namespace

std::vector<PointRef> PlaneExtraction::pointsOf(const PlaneFeature& plane) const {
  std::vector<PointRef> out;
  out.reserve(plane.pointCount());
  std::uint32_t frame = 0;
  for (std::uint32_t k = plane.first_point; k < plane.end_point; ++k) {
    const std::uint32_t id = point_ids[k];
    while (id >= first_id[frame + 1]) ++frame;  // ids ascend: frames come in order
    out.push_back({frame, id - first_id[frame]});
  }
  return out;
}

std::vector<std::vector<std::uint32_t>> PlaneExtraction::pointIndicesPerScan() const {
  // Marks instead of sorting: linear in the points, and keyframes hold millions.
  const std::size_t scans = first_id.empty() ? 0 : first_id.size() - 1;
  std::vector<bool> used(first_id.empty() ? 0 : first_id.back(), false);
  for (const PlaneFeature& plane : planes) {
    for (std::uint32_t k = plane.first_point; k < plane.end_point; ++k) used[point_ids[k]] = true;
  }
  std::vector<std::vector<std::uint32_t>> indices(scans);
  for (std::size_t f = 0; f < scans; ++f) {
    for (std::uint32_t id = first_id[f]; id < first_id[f + 1]; ++id) {
      if (used[id]) indices[f].push_back(id - first_id[f]);
    }
  }
  return indices;
}

PlaneExtraction extractPlanes(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                              const PlaneSettings& settings) {
  validate(scans, poses, settings);
  const WorldPoints world = placeInWorld(scans, poses);
  return planesOfCells(world, assignCells(world.position, settings.voxel_size, kPointsPerPlaneVoxel),
                       settings);
}

PlaneExtraction extractPlanes(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                              const PlaneSettings& settings, std::size_t share, std::size_t shares) {
  if (shares == 0 || share >= shares) {
    throw Error("plane extraction: share " + std::to_string(share) + " of " + std::to_string(shares));
  }
  if (shares == 1) return extractPlanes(scans, poses, settings);
  validate(scans, poses, settings);
  // The frames' placement and point offsets, no points placed yet.
  const WorldPoints frames = placeInWorld(scans, poses, /*with_points=*/false);
  const KeyOf keyOf(settings.voxel_size);
  const std::vector<std::int64_t> bounds = shareBounds(scans, frames, keyOf, shares);
  const std::int64_t low = share == 0 ? std::numeric_limits<std::int64_t>::min() : bounds[share - 1];
  const std::int64_t high = share + 1 == shares ? std::numeric_limits<std::int64_t>::max() : bounds[share];
  // A root voxel lies in one share whole (its points share its x index):
  // the share's points, in id order, make the very voxels one extraction
  // over every point makes there. Only they are placed and hashed.
  std::vector<std::uint32_t> ids;
  const WorldPoints world = placeShareInWorld(scans, frames, keyOf, low, high, ids);
  PlaneExtraction out =
      planesOfCells(world, assignCells(world.position, settings.voxel_size, kPointsPerPlaneVoxel), settings);
  for (std::uint32_t& id : out.point_ids) id = ids[id];  // as one extraction numbers them
  out.first_id = frames.first;
  return out;
}

std::pair<PlaneExtraction, PlaneExtraction> extractPlanesAtTwoVoxels(
    const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
    const PlaneSettings& settings, double fine_voxel) {
  validate(scans, poses, settings);
  if (!(fine_voxel > 0.0 && fine_voxel <= settings.voxel_size)) {
    throw Error("plane extraction: the finer voxel must be in (0, voxel_size]");
  }
  PlaneSettings fine_settings = settings;
  fine_settings.voxel_size = fine_voxel;
  const WorldPoints world = placeInWorld(scans, poses);
  CellAssignment fine = assignCells(world.position, fine_voxel, kPointsPerPlaneVoxel);
  std::optional<CellAssignment> coarse = coarsenCells(fine, world.position, settings.voxel_size);
  if (!coarse) coarse = assignCells(world.position, settings.voxel_size, kPointsPerPlaneVoxel);
  PlaneExtraction coarse_planes = planesOfCells(world, std::move(*coarse), settings);
  return {std::move(coarse_planes), planesOfCells(world, std::move(fine), fine_settings)};
}

}  // namespace hba::voxel
