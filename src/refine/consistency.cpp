#include "consistency.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <type_traits>

#include <tbb/parallel_for.h>

#include "hba/core/error.hpp"

namespace hba::refine {

FixedPlaneMap::FixedPlaneMap(const ba::PlaneProblem& problem, std::size_t frames, std::size_t regions) {
  std::size_t total = 0;
  for (const ba::PlaneObservation& plane : problem.planes()) total += plane.clusters.size();
  clusters_.reserve(total);
  plane_begin_.reserve(problem.numPlanes() + 1);
  for (const ba::PlaneObservation& plane : problem.planes()) {
    for (const ba::FrameCluster& fc : plane.clusters) {
      CompactCluster c;
      c.frame = fc.frame;
      c.count = static_cast<float>(fc.count());
      c.mean = {static_cast<float>(fc.mean().x()), static_cast<float>(fc.mean().y()),
                static_cast<float>(fc.mean().z())};
      const Mat3 S = fc.scatter();
      c.scatter = {static_cast<float>(S(0, 0)), static_cast<float>(S(0, 1)), static_cast<float>(S(0, 2)),
                   static_cast<float>(S(1, 1)), static_cast<float>(S(1, 2)), static_cast<float>(S(2, 2))};
      clusters_.push_back(c);
    }
    plane_begin_.push_back(clusters_.size());
  }
  frames = std::max<std::size_t>(1, frames);
  regions = std::clamp<std::size_t>(regions, 1, frames);
  for (std::size_t r = 0; r < regions; ++r) region_starts_.push_back(r * frames / regions);
  region_points_.assign(regions, 0.0);
  // Each plane's points and region; of every member's planes, in order,
  // when the problem is spread over a group.
  std::vector<double> figures;
  for (const ba::PlaneObservation& plane : problem.planes()) {
    const std::size_t first = plane.clusters.front().frame;
    figures.push_back(plane.pointCount());
    figures.push_back(static_cast<double>(std::min(regions - 1, first * regions / frames)));
  }
  if (problem.spread().spread()) {
    group_ = problem.spread().group;
    figures = ba::gatherInOrder(*group_, figures);
  }
  for (std::size_t k = 0; k + 1 < figures.size(); k += 2) {
    const auto region = static_cast<std::size_t>(figures[k + 1]);
    plane_region_.push_back(region);
    plane_points_.push_back(figures[k]);
    region_points_[region] += figures[k];
    points_ += figures[k];
  }
}

std::vector<double> FixedPlaneMap::planeCosts(const std::vector<Pose>& poses) const {
  const ba::FrameTransforms frames(poses);
  std::vector<double> costs(plane_begin_.size() - 1);
  tbb::parallel_for(std::size_t{0}, costs.size(), [&](std::size_t p) {
    thread_local ba::PlaneObservation plane;  // reused: no allocation per plane
    plane.clusters.clear();
    for (std::size_t k = plane_begin_[p]; k < plane_begin_[p + 1]; ++k) {
      const CompactCluster& c = clusters_[k];
      ba::PointCluster points;
      points.count = c.count;
      points.mean = Vec3(c.mean[0], c.mean[1], c.mean[2]);
      const auto& v = c.scatter;
      points.scatter << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
      plane.clusters.emplace_back(c.frame, points);
    }
    costs[p] = ba::planeCost(plane, frames);
  });
  return group_ ? ba::gatherInOrder(*group_, costs) : costs;
}

namespace {

template <typename T>
void writeVector(std::ofstream& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof(n));
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

template <typename T>
void readVector(std::ifstream& in, std::vector<T>& v) {
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof(n));
  if (!in) return;
  v.resize(static_cast<std::size_t>(n));
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

}  // namespace

void FixedPlaneMap::save(const std::filesystem::path& path) const {
  static_assert(std::is_trivially_copyable_v<CompactCluster>);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  writeVector(out, clusters_);
  writeVector(out, plane_begin_);
  writeVector(out, plane_region_);
  writeVector(out, plane_points_);
  writeVector(out, region_points_);
  writeVector(out, region_starts_);
  out.write(reinterpret_cast<const char*>(&points_), sizeof(points_));
  out.close();
  if (!out) failAt(path, "cannot write a kept self-check map (disk full?)");
}

FixedPlaneMap FixedPlaneMap::load(const std::filesystem::path& path, const dist::Group* group) {
  std::ifstream in(path, std::ios::binary);
  FixedPlaneMap map;
  map.group_ = group != nullptr && group->size() > 1 ? group : nullptr;
  readVector(in, map.clusters_);
  readVector(in, map.plane_begin_);
  readVector(in, map.plane_region_);
  readVector(in, map.plane_points_);
  readVector(in, map.region_points_);
  readVector(in, map.region_starts_);
  in.read(reinterpret_cast<char*>(&map.points_), sizeof(map.points_));
  if (!in || map.plane_begin_.empty()) failAt(path, "cannot read a kept self-check map");
  return map;
}

double FixedPlaneMap::rmsOf(const std::vector<double>& costs) const {
  if (!(points_ > 0.0)) return 0.0;
  double cost = 0.0;
  for (double c : costs) cost += c;  // fixed order: deterministic
  return std::sqrt(cost / points_);
}

double FixedPlaneMap::rms(const std::vector<Pose>& poses) const { return rmsOf(planeCosts(poses)); }

std::vector<double> FixedPlaneMap::regionRms(const std::vector<Pose>& poses) const {
  return regionRmsOf(planeCosts(poses));
}

FixedPlaneMap::Figures FixedPlaneMap::figures(const std::vector<Pose>& poses) const {
  const std::vector<double> costs = planeCosts(poses);
  return {rmsOf(costs), regionRmsOf(costs)};
}

std::vector<double> FixedPlaneMap::regionRmsOf(const std::vector<double>& costs) const {
  std::vector<double> sums(region_points_.size(), 0.0);
  for (std::size_t p = 0; p < costs.size(); ++p) sums[plane_region_[p]] += costs[p];
  for (std::size_t r = 0; r < sums.size(); ++r) {
    sums[r] = region_points_[r] > 0.0 ? std::sqrt(sums[r] / region_points_[r]) : 0.0;
  }
  return sums;
}

}  // namespace hba::refine
