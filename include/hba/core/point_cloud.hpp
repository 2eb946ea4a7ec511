#pragma once
// A scan: float xyz points in the sensor frame, with optional intensity
// and, for a raw sweep, each point's time as recorded.
// A map far from the world origin (UTM, ECEF) keeps its float precision by
// storing points relative to `origin` (double): world = origin + point.
#include <cstddef>
#include <vector>

#include "hba/core/types.hpp"

namespace hba {

// Names drivers give a point's time, in the order one is chosen: Ouster's
// t, Velodyne's time, Hesai's and Livox driver 2's timestamp, Livox's offset_time.
inline constexpr const char* kPointTimeFields[] = {"t", "time", "timestamp", "offset_time"};

struct PointCloud {
  std::vector<Vec3f> points;
  std::vector<float> intensity;  // empty, or one value per point
  // Empty, or one value per point: when it was measured, as the file stores
  // it (unit and origin unknown until io::readPointTimes interprets them).
  std::vector<double> time;
  Vec3 origin = Vec3::Zero();  // metres; zero for scans, may be set for maps

  // Point i in the frame `origin` refers to, in double.
  Vec3 world(std::size_t i) const { return origin + points[i].cast<double>(); }

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasIntensity() const { return !intensity.empty(); }
  bool hasTime() const { return !time.empty(); }
  void reserve(std::size_t n, bool with_intensity);
  void clear();
  // Appends a point. Use one overload for a whole cloud: with intensity or without.
  void add(const Vec3f& p) { points.push_back(p); }
  void add(const Vec3f& p, float value) {
    points.push_back(p);
    intensity.push_back(value);
  }
};

}  // namespace hba
