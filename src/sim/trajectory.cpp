#include "hba/sim/trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "closed_curve.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "procedural_path.hpp"

namespace hba::sim {
namespace {

using Vec2 = Eigen::Vector2d;

// Fraction of the driven distance one lap takes: the last ~20 % revisit the start.
constexpr double kLapFraction = 0.8;
// Half the distance between the two lanes of the street (its turning radius).
constexpr double kStreetHalfWidth = 7.0;

// A rounded rectangle of outer size width x height and corner radius r,
// traced counter-clockwise from the middle of its bottom edge.
Vec2 roundedRectangle(double u, double width, double height, double r) {
  const double sx = width - 2.0 * r;  // straight lengths
  const double sy = height - 2.0 * r;
  const double arc = 0.5 * M_PI * r;
  const std::array<double, 8> lengths{sx, arc, sy, arc, sx, arc, sy, arc};
  double total = 0.0;
  for (double l : lengths) total += l;
  double s = u * total + 0.5 * sx;  // start mid bottom edge
  s = std::fmod(s, total);
  const double hx = 0.5 * sx, hy = 0.5 * sy;
  const std::array<Vec2, 4> corners{Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy), Vec2(-hx, -hy)};
  const std::array<Vec2, 4> edge_start{Vec2(-hx, -hy - r), Vec2(hx + r, -hy), Vec2(hx, hy + r),
                                       Vec2(-hx - r, hy)};
  const std::array<Vec2, 4> edge_direction{Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)};
  for (int side = 0; side < 4; ++side) {
    const double straight = lengths[2 * side];
    if (s <= straight) return edge_start[side] + s * edge_direction[side];
    s -= straight;
    if (s <= arc || side == 3) {
      const double angle = -0.5 * M_PI + side * 0.5 * M_PI + std::min(s, arc) / r;
      return corners[side] + r * Vec2(std::cos(angle), std::sin(angle));
    }
    s -= arc;
  }
  return edge_start[0];
}

// The shape's closed curve, scaled so one lap is `perimeter` metres.
ClosedCurve curveFor(PathShape shape, double perimeter) {
  switch (shape) {
    case PathShape::Block: {
      const ClosedCurve unit([](double u) -> Vec2 { return roundedRectangle(u, 1.5, 1.0, 0.2); });
      const double scale = perimeter / unit.perimeter();
      return ClosedCurve([scale](double u) -> Vec2 { return roundedRectangle(u, 1.5, 1.0, 0.2) * scale; });
    }
    case PathShape::Figure8: {
      // Lemniscate of Gerono: crosses itself at the origin.
      auto gerono = [](double u) -> Vec2 {
        const double a = 2.0 * M_PI * u;
        return Vec2(std::sin(a), 0.5 * std::sin(2.0 * a));
      };
      const double scale = perimeter / ClosedCurve(gerono).perimeter();
      return ClosedCurve([gerono, scale](double u) -> Vec2 { return gerono(u) * scale; });
    }
    case PathShape::Street: {
      // The lanes keep their real spacing; only the street's length scales.
      const double r = kStreetHalfWidth;
      const double length = std::max(20.0, 0.5 * (perimeter - 2.0 * M_PI * r));
      return ClosedCurve([=](double u) -> Vec2 { return roundedRectangle(u, length + 2 * r, 2 * r, r); });
    }
  }
  throw Error("unknown path shape");
}

double lapLength(PathShape shape, double distance) {
  const double wanted = kLapFraction * distance;
  switch (shape) {
    case PathShape::Block:
      return std::clamp(wanted, 100.0, 1200.0);
    case PathShape::Figure8:
      return std::clamp(wanted, 120.0, 1200.0);
    case PathShape::Street:
      return std::clamp(wanted, 140.0, 2400.0);
  }
  return wanted;
}

PlanarPath proceduralPath(const TrajectoryConfig& config) {
  return walkCurve(pathCurve(config), 0.0, config.speed / config.frame_rate_hz, config.frames, false);
}

}  // namespace

ClosedCurve pathCurve(const TrajectoryConfig& config) {
  const double step = config.speed / config.frame_rate_hz;
  const double distance = step * static_cast<double>(config.frames);
  return curveFor(config.shape, lapLength(config.shape, distance));
}

PlanarPath walkCurve(const ClosedCurve& curve, double start, double step, std::size_t frames, bool reverse) {
  const double direction = reverse ? -1.0 : 1.0;
  PlanarPath path;
  for (std::size_t k = 0; k < frames; ++k) {
    path.positions.push_back(curve.at(start + direction * step * static_cast<double>(k)));
  }
  // Heading along the direction of travel (central difference on the curve itself).
  for (std::size_t k = 0; k < frames; ++k) {
    const double s = start + direction * step * static_cast<double>(k);
    const Vec2 tangent = direction * (curve.at(s + 0.25) - curve.at(s - 0.25));
    path.headings.push_back(std::atan2(tangent.y(), tangent.x()));
  }
  return path;
}

PlanarPath planarPathFromFile(const std::filesystem::path& file, std::size_t max_poses) {
  const io::PoseFormat format = io::detectPoseFormat(file);
  const Trajectory trajectory = io::readPoses(file, format);
  if (trajectory.empty()) failAt(file, "the trajectory file holds no poses");
  Mat3 camera_to_lidar = Mat3::Identity();
  if (format == io::PoseFormat::Kitti) {
    camera_to_lidar << 0, 0, 1,  //
        -1, 0, 0,                //
        0, -1, 0;
  }
  PlanarPath path;
  const std::size_t count = std::min(max_poses, trajectory.size());
  for (std::size_t k = 0; k < count; ++k) {
    const Pose& pose = trajectory.poses[k];
    const Vec3 position = camera_to_lidar * pose.t;
    const Mat3 rotation = camera_to_lidar * pose.R() * camera_to_lidar.transpose();
    const Vec3 forward = rotation.col(0);
    path.positions.emplace_back(position.x(), position.y());
    path.headings.push_back(std::atan2(forward.y(), forward.x()));
  }
  return path;
}

Trajectory drapeOnTerrain(const PlanarPath& path, const Terrain& terrain, double sensor_height,
                          double frame_rate_hz) {
  Trajectory trajectory;
  for (std::size_t k = 0; k < path.positions.size(); ++k) {
    const Vec2& p = path.positions[k];
    const double yaw = path.headings[k];
    const Vec2 forward(std::cos(yaw), std::sin(yaw));
    const Vec2 left(-forward.y(), forward.x());
    const Vec2 slope = terrain.gradient(p.x(), p.y());
    // Nose up on a rising road is a negative rotation about y (x turns to +z).
    const double pitch = -std::atan(slope.dot(forward));
    const double roll = std::atan(slope.dot(left));
    const Mat3 rotation = (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                           Eigen::AngleAxisd(roll, Vec3::UnitX()))
                              .toRotationMatrix();
    const Vec3 position(p.x(), p.y(), terrain.height(p.x(), p.y()) + sensor_height);
    trajectory.poses.emplace_back(rotation, position);
    trajectory.stamps.push_back(static_cast<double>(k) / frame_rate_hz);
  }
  return trajectory;
}

Trajectory makeTrajectory(const TrajectoryConfig& config, const Terrain& terrain) {
  if (config.frames == 0) throw Error("simulate: the number of frames must be positive");
  if (!(config.frame_rate_hz > 0.0)) throw Error("simulate: the frame rate must be positive");
  if (!(config.sensor_height > 0.0)) throw Error("simulate: the sensor height must be positive");
  if (!config.file.empty()) {
    return drapeOnTerrain(planarPathFromFile(config.file, config.frames), terrain, config.sensor_height,
                          config.frame_rate_hz);
  }
  if (!(config.speed > 0.0) || config.speed > 100.0) {
    throw Error("simulate: the speed must be in (0, 100] m/s");
  }
  return drapeOnTerrain(proceduralPath(config), terrain, config.sensor_height, config.frame_rate_hz);
}

}  // namespace hba::sim
