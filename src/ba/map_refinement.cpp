#include "hba/ba/map_refinement.hpp"

#include <cmath>
#include <unordered_set>

#include "hba/core/error.hpp"

namespace hba::ba {
namespace {

struct CellHash {
  std::size_t operator()(const Eigen::Vector3i& c) const {
    return static_cast<std::size_t>(c.x()) * 73856093u ^ static_cast<std::size_t>(c.y()) * 19349663u ^
           static_cast<std::size_t>(c.z()) * 83492791u;
  }
};

Eigen::Vector3i cellOf(const Vec3& p, double edge) { return (p / edge).array().floor().cast<int>(); }

}  // namespace

PointCloud mapNear(const PointCloud& map, const std::vector<Pose>& poses, double reach) {
  if (!(reach > 0.0)) throw Error("map refinement: the reach must be positive");
  // Cells of edge `reach` holding a pose, and their neighbours: every point
  // within reach of a pose is in one (some a little farther are too).
  std::unordered_set<Eigen::Vector3i, CellHash> near;
  for (const Pose& pose : poses) {
    const Eigen::Vector3i c = cellOf(pose.t, reach);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) near.insert(c + Eigen::Vector3i(dx, dy, dz));
  }
  PointCloud out;
  out.origin = map.origin;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (near.count(cellOf(map.points[i].cast<double>(), reach)) > 0) {
      if (map.hasIntensity()) {
        out.add(map.points[i], map.intensity[i]);
      } else {
        out.add(map.points[i]);
      }
    }
  }
  return out;
}

RefinementResult refineAgainstMap(const PointCloud& map, const std::vector<const PointCloud*>& scans,
                                  const std::vector<Pose>& poses, RefinementSettings settings) {
  if (scans.size() != poses.size()) throw Error("map refinement: pose and scan counts differ");
  // The map as frame 0, its points in map coordinates (no origin: the
  // poses are relative to it too), held fixed as the gauge.
  PointCloud local = map;
  local.origin = Vec3::Zero();
  std::vector<const PointCloud*> all{&local};
  all.insert(all.end(), scans.begin(), scans.end());
  std::vector<Pose> initial{Pose()};
  initial.insert(initial.end(), poses.begin(), poses.end());
  // No motion prior between the map and the session's first frame: a path
  // so long that its prior weighs nothing.
  std::vector<double> steps{1e9};
  for (std::size_t i = 1; i < poses.size(); ++i) steps.push_back((poses[i].t - poses[i - 1].t).norm());
  settings.lm.hold_first = true;
  RefinementResult result = refineGlobally(all, initial, settings, steps, initial);
  result.poses.erase(result.poses.begin());
  return result;
}

}  // namespace hba::ba
