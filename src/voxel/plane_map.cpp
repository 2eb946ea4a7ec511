#include "hba/voxel/plane_map.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include "hba/core/error.hpp"
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

WorldPoints placeInWorld(const std::vector<const PointCloud*>& scans,
                         const std::vector<Pose>& poses) {
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

// Eigenvalues (ascending) of the covariance of the points `ids`.
Vec3 covarianceEigenvalues(const WorldPoints& world, const std::vector<std::uint32_t>& ids) {
  Vec3 mean = Vec3::Zero();
  for (std::uint32_t id : ids) mean += world.position[id].cast<double>();
  mean /= static_cast<double>(ids.size());
  Mat3 cov = Mat3::Zero();
  for (std::uint32_t id : ids) {
    const Vec3 d = world.position[id].cast<double>() - mean;
    cov.noalias() += d * d.transpose();
  }
  cov /= static_cast<double>(ids.size());
  return Eigen::SelfAdjointEigenSolver<Mat3>(cov, Eigen::EigenvaluesOnly).eigenvalues();
}

int countFrames(const WorldPoints& world, const std::vector<std::uint32_t>& ids) {
  int frames = 0;
  std::uint32_t last = std::numeric_limits<std::uint32_t>::max();
  for (std::uint32_t id : ids) {  // ids are sorted, so frames come in runs
    if (world.frame[id] != last) ++frames;
    last = world.frame[id];
  }
  return frames;
}

class OctreeSplitter {
 public:
  OctreeSplitter(const WorldPoints& world, const PlaneSettings& settings)
      : world_(world), settings_(settings) {}

  // Tests the cell [corner, corner + edge)^3 holding `ids`; appends its planes.
  void visit(const std::vector<std::uint32_t>& ids, const Vec3& corner, double edge, int depth,
             std::vector<PlaneFeature>& out) const {
    if (static_cast<int>(ids.size()) < settings_.min_points) return;
    if (passesPlaneTest(covarianceEigenvalues(world_, ids), settings_)) {
      if (countFrames(world_, ids) >= settings_.min_frames) out.push_back(toFeature(ids, depth));
      return;
    }
    if (depth >= settings_.max_depth) return;
    const double half = 0.5 * edge;
    const Vec3 center = corner + Vec3::Constant(half);
    std::vector<std::uint32_t> octants[8];
    for (std::uint32_t id : ids) {
      const Vec3f& p = world_.position[id];
      const int octant = (p.x() >= center.x() ? 1 : 0) | (p.y() >= center.y() ? 2 : 0) |
                         (p.z() >= center.z() ? 4 : 0);
      octants[octant].push_back(id);
    }
    for (int o = 0; o < 8; ++o) {
      const Vec3 child_corner = corner + half * Vec3((o & 1) ? 1 : 0, (o & 2) ? 1 : 0,
                                                     (o & 4) ? 1 : 0);
      visit(octants[o], child_corner, half, depth + 1, out);
    }
  }

 private:
  PlaneFeature toFeature(const std::vector<std::uint32_t>& ids, int depth) const {
    PlaneFeature feature;
    feature.depth = depth;
    feature.points.reserve(ids.size());
    for (std::uint32_t id : ids) {
      const std::uint32_t f = world_.frame[id];
      feature.points.push_back({f, static_cast<std::uint32_t>(id - world_.first[f])});
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
    throw Error("plane extraction: invalid settings (need voxel_size > 0, eigen_ratio > 0, "
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

std::vector<PlaneFeature> extractPlanes(const std::vector<const PointCloud*>& scans,
                                        const std::vector<Pose>& poses,
                                        const PlaneSettings& settings) {
  validate(scans, poses, settings);
  const WorldPoints world = placeInWorld(scans, poses);

  // Root voxels; each id list stays sorted because ids are visited in order.
  std::unordered_map<VoxelKey, std::size_t, VoxelKeyHash> voxel_of_key;
  std::vector<VoxelKey> keys;
  std::vector<std::vector<std::uint32_t>> members;
  for (std::size_t id = 0; id < world.position.size(); ++id) {
    const VoxelKey key = VoxelKey::of(world.position[id].cast<double>(), settings.voxel_size);
    const auto [it, inserted] = voxel_of_key.try_emplace(key, keys.size());
    if (inserted) {
      keys.push_back(key);
      members.emplace_back();
    }
    members[it->second].push_back(static_cast<std::uint32_t>(id));
  }

  // Visit voxels in key order so the output never depends on the hash.
  std::vector<std::size_t> order(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });

  const OctreeSplitter splitter(world, settings);
  std::vector<std::vector<PlaneFeature>> per_voxel(order.size());
  tbb::parallel_for(std::size_t{0}, order.size(), [&](std::size_t i) {
    const VoxelKey& key = keys[order[i]];
    const Vec3 corner = settings.voxel_size * Vec3(static_cast<double>(key.x),
                                                   static_cast<double>(key.y),
                                                   static_cast<double>(key.z));
    splitter.visit(members[order[i]], corner, settings.voxel_size, 0, per_voxel[i]);
  });

  std::vector<PlaneFeature> planes;
  for (auto& found : per_voxel) {
    for (auto& plane : found) planes.push_back(std::move(plane));
  }
  return planes;
}

}  // namespace hba::voxel
