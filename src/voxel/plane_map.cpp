#include "hba/voxel/plane_map.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cell_assignment.hpp"
#include "hba/core/error.hpp"
#include "hba/core/shifted_moments.hpp"
#include "hba/core/symmetric_eigenvalues.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

// All window points in the world, addressed by a global id (scans in order,
// points in order), so that ids in a voxel are sorted by (frame, index).
struct WorldPoints {
  std::vector<Vec3f> position;       // float: only used for the plane test
  std::vector<std::uint32_t> frame;  // owning scan of each id
  std::vector<std::size_t> first;    // first global id of each scan
};

WorldPoints placeInWorld(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses) {
  WorldPoints world;
  std::size_t total = 0;
  for (const PointCloud* scan : scans) {
    world.first.push_back(total);
    total += scan->size();
  }
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("plane extraction: more than 2^32 points in one window");
  }
  world.position.resize(total);
  world.frame.resize(total);
  tbb::parallel_for(std::size_t{0}, scans.size(), [&](std::size_t f) {
    const Mat3 R = poses[f].R();
    const Vec3& t = poses[f].t;
    const auto& points = scans[f]->points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      world.position[world.first[f] + i] = (R * points[i].cast<double>() + t).cast<float>();
      world.frame[world.first[f] + i] = static_cast<std::uint32_t>(f);
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

int countFrames(const WorldPoints& world, IdSpan ids) {
  int frames = 0;
  std::uint32_t last = std::numeric_limits<std::uint32_t>::max();
  for (const std::uint32_t* id = ids.begin; id != ids.end; ++id) {  // frames come in runs
    if (world.frame[*id] != last) ++frames;
    last = world.frame[*id];
  }
  return frames;
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
  OctreeSplitter(const WorldPoints& world, const PlaneSettings& settings)
      : world_(world), settings_(settings) {}

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
      if (countFrames(world_, ids) >= settings_.min_frames) out.push_back(toFeature(ids, depth));
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
  PlaneFeature toFeature(IdSpan ids, int depth) const {
    PlaneFeature feature;
    feature.depth = depth;
    feature.points.reserve(ids.size());
    for (const std::uint32_t* id = ids.begin; id != ids.end; ++id) {
      const std::uint32_t f = world_.frame[*id];
      feature.points.push_back({f, static_cast<std::uint32_t>(*id - world_.first[f])});
    }
    return feature;
  }

  const WorldPoints& world_;
  const PlaneSettings& settings_;
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
std::vector<PlaneFeature> planesOfCells(const WorldPoints& world, const CellAssignment& cells,
                                        const PlaneSettings& settings) {
  // Root voxels, their ids ascending (counting sort by cell).
  CellMembers members = membersOf(cells);
  std::vector<VoxelKey> keys(cells.cells());
  for (std::size_t c = 0; c < keys.size(); ++c) {
    keys[c] = VoxelKey::of(world.position[cells.first_point_of_cell[c]].cast<double>(), settings.voxel_size);
  }

  // Visit voxels in key order so the output never depends on the hash.
  std::vector<std::size_t> order(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });

  const OctreeSplitter splitter(world, settings);
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

  std::vector<PlaneFeature> planes;
  for (auto& found : per_voxel) {
    for (auto& plane : found) planes.push_back(std::move(plane));
  }
  return planes;
}

}  // namespace

std::vector<PlaneFeature> extractPlanes(const std::vector<const PointCloud*>& scans,
                                        const std::vector<Pose>& poses, const PlaneSettings& settings) {
  validate(scans, poses, settings);
  const WorldPoints world = placeInWorld(scans, poses);
  return planesOfCells(world, assignCells(world.position, settings.voxel_size, kPointsPerPlaneVoxel),
                       settings);
}

std::pair<std::vector<PlaneFeature>, std::vector<PlaneFeature>> extractPlanesAtTwoVoxels(
    const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
    const PlaneSettings& settings, double fine_voxel) {
  validate(scans, poses, settings);
  if (!(fine_voxel > 0.0 && fine_voxel <= settings.voxel_size)) {
    throw Error("plane extraction: the finer voxel must be in (0, voxel_size]");
  }
  PlaneSettings fine_settings = settings;
  fine_settings.voxel_size = fine_voxel;
  const WorldPoints world = placeInWorld(scans, poses);
  const CellAssignment fine = assignCells(world.position, fine_voxel, kPointsPerPlaneVoxel);
  std::optional<CellAssignment> coarse = coarsenCells(fine, world.position, settings.voxel_size);
  if (!coarse) coarse = assignCells(world.position, settings.voxel_size, kPointsPerPlaneVoxel);
  return {planesOfCells(world, *coarse, settings), planesOfCells(world, fine, fine_settings)};
}

}  // namespace hba::voxel
