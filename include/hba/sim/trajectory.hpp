#pragma once
// Ground-truth vehicle paths for the simulator.
//
// Every path is planar (x, y) and then draped on the terrain: the sensor sits
// `sensor_height` above the ground, heading along the path's tangent, pitched
// and rolled with the local slope. Poses are sensor-to-world, sensor frame
// x forward, y left, z up; one pose per frame at `frame_rate_hz`.
#include <filesystem>
#include <optional>
#include <string>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/sim/terrain.hpp"

namespace hba::sim {

// Procedural loops, each revisited: a city-block tour (rounded rectangle), a
// figure eight (crossing itself), a long street that turns and comes back on
// the opposite lane. A loop's perimeter is sized to ~80 % of the distance
// driven (within limits), so a sequence ends by revisiting where it started.
enum class PathShape { Block, Figure8, Street };

struct TrajectoryConfig {
  PathShape shape = PathShape::Block;
  // If set, follow this trajectory file (KITTI/TUM/HBA, via io::readPoses)
  // instead of `shape`; see trajectoryFromFile.
  std::filesystem::path file;
  std::size_t frames = 300;
  double speed = 5.0;           // m/s (procedural shapes only)
  double frame_rate_hz = 10.0;  // timestamps are index / rate
  double sensor_height = 1.8;   // m above the ground
};

// Throws hba::Error for non-positive frames/speed/rate or an unreadable file.
// A file shorter than `frames` yields as many frames as it has poses.
Trajectory makeTrajectory(const TrajectoryConfig& config, const Terrain& terrain);

// Planar positions and headings of a trajectory file, converted to a frame
// with z up. KITTI files hold camera poses (x right, y down, z forward) in a
// camera-convention world, so they are re-expressed with the fixed axis swap
// C (x_lidar = z_cam, y_lidar = -x_cam, z_lidar = -y_cam): T_lidar = C T_cam C^T.
// TUM and HBA files are taken as already z-up. At most `max_poses` are read.
struct PlanarPath {
  std::vector<Eigen::Vector2d> positions;
  std::vector<double> headings;  // yaw (rad) of the vehicle's x axis
};
PlanarPath planarPathFromFile(const std::filesystem::path& file, std::size_t max_poses);

// Places a planar path on the terrain (z, pitch and roll from the ground).
Trajectory drapeOnTerrain(const PlanarPath& path, const Terrain& terrain, double sensor_height,
                          double frame_rate_hz);

}  // namespace hba::sim

namespace hba {
template <>
struct EnumNames<sim::PathShape> {
  static constexpr const char* what = "path shape";
  static constexpr EnumName<sim::PathShape> names[] = {{sim::PathShape::Block, "block"},
                                                       {sim::PathShape::Figure8, "figure8"},
                                                       {sim::PathShape::Street, "street"}};
};
}  // namespace hba
