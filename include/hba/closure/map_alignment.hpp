#pragma once
// Placing a session in a fixed map's frame (a prior map: `hba optimize NEW
// --map MAP`). The map, a point cloud of any size, is cut into overlapping
// tiles, each described like a place of a session (docs/closure.md); the
// session's places are matched against the tiles, registered, verified by
// the plane BA, and the placements of the verified pairs must agree.
#include "hba/closure/session_alignment.hpp"
#include "hba/core/point_cloud.hpp"

namespace hba::closure {

struct MapTiling {
  // Tile radius in descriptor voxels (twice a place scan's median range):
  // a tile holds what a place's submap sees.
  double radius_voxels = 40.0;
  std::size_t min_points = 200;  // tiles with fewer points (at the tile voxel) are left out
};

struct MapAlignment : SessionAlignment {
  std::size_t tiles = 0;
  double tile_radius_m = 0.0;
  double map_extent_m = 0.0;  // the map's bounding-box diagonal, for messages
};

// `world_from_session` maps the session's frame into the map's point
// coordinates (relative to map.origin). Deterministic.
MapAlignment alignToMap(const PointCloud& map, const io::ScanSource& session_scans,
                        const std::vector<Pose>& session_poses, const SessionAlignmentSettings& settings,
                        const MapTiling& tiling = {});

}  // namespace hba::closure
