#include "hba/closure/map_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/kd_tree.hpp"
#include "hba/core/error.hpp"
#include "hba/voxel/downsample.hpp"
#include "place_alignment.hpp"

namespace hba::closure {
namespace {

struct Tiles {
  std::vector<PointCloud> clouds;  // points relative to their centre
  std::vector<Pose> poses;         // translations to the centres
};

// Tiles of radius `radius` centred on the centroids of the map's occupied
// cells of edge `radius`: every place of the map lies in one whose centre is
// within 0.9 radius, and the tiles overlap. In cell order: deterministic.
Tiles cutTiles(const PointCloud& sparse, double radius, std::size_t min_points) {
  std::map<std::tuple<long, long, long>, std::pair<Vec3, std::size_t>> cells;
  for (const Vec3f& p : sparse.points) {
    const Vec3 q = p.cast<double>();
    // Eigen leaves a default-built vector unset: each cell starts at zero
    // explicitly (else its centroid, and the tiles, varied run to run).
    auto& [sum, count] = cells
                             .try_emplace({static_cast<long>(std::floor(q.x() / radius)),
                                           static_cast<long>(std::floor(q.y() / radius)),
                                           static_cast<long>(std::floor(q.z() / radius))},
                                          Vec3::Zero(), std::size_t{0})
                             .first->second;
    sum += q;
    ++count;
  }
  const KdTree<3> tree(sparse.points);
  Tiles tiles;
  for (const auto& [key, cell] : cells) {
    const Vec3 centre = cell.first / static_cast<double>(cell.second);
    PointCloud tile;
    for (const auto& [i, d] : tree.within(centre.cast<float>(), static_cast<float>(radius))) {
      tile.add((sparse.points[i].cast<double>() - centre).cast<float>());
    }
    if (tile.size() < min_points) continue;
    tiles.clouds.push_back(std::move(tile));
    tiles.poses.emplace_back(Quat::Identity(), centre);
  }
  return tiles;
}

double extent(const PointCloud& cloud) {
  if (cloud.empty()) return 0.0;
  Vec3f low = cloud.points.front(), high = low;
  for (const Vec3f& p : cloud.points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return static_cast<double>((high - low).norm());
}

}  // namespace

MapAlignment alignToMap(const PointCloud& map, const io::ScanSource& session_scans,
                        const std::vector<Pose>& session_poses, const SessionAlignmentSettings& settings,
                        const MapTiling& tiling) {
  if (session_poses.size() != session_scans.size()) throw Error("map alignment: pose and scan counts differ");
  if (session_poses.empty()) throw Error("map alignment: a session without scans");
  MapAlignment result;
  result.map_extent_m = extent(map);
  const Side session{session_scans, session_poses,
                     samplePlaces(session_poses, settings.sample_spacing_m, settings.max_samples), false};
  const double voxel = settings.feature_voxel_m > 0.0 ? settings.feature_voxel_m : featureVoxel({&session});
  result.tile_radius_m = tiling.radius_voxels * voxel;
  // The tiles at a quarter of the descriptor voxel: fine enough for the
  // plane BA that verifies a pair, as a session's merged submaps are.
  const Tiles tiles = cutTiles(voxel::downsample(map, std::max(0.1, voxel / 4.0), 4), result.tile_radius_m,
                               tiling.min_points);
  result.tiles = tiles.clouds.size();
  if (tiles.clouds.empty()) {
    result.feature_voxel_m = voxel;
    result.reason = "the map has no tile of " + std::to_string(tiling.min_points) + " points within " +
                    std::to_string(static_cast<int>(std::round(result.tile_radius_m))) + " m";
    return result;
  }
  const io::MemoryScanSource tile_scans(tiles.clouds);
  std::vector<std::size_t> all(tiles.clouds.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  const Side reference{tile_scans, tiles.poses, all, true};
  const SessionAlignment found = alignSides(reference, session, voxel, settings);
  static_cast<SessionAlignment&>(result) = found;
  return result;
}

}  // namespace hba::closure
