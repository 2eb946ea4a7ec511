#pragma once
// A scan: float xyz points in the sensor frame, with optional intensity.
// A map far from the world origin (UTM, ECEF) keeps its float precision by
// storing points relative to `origin` (double): world = origin + point.
#include <cstddef>
#include <vector>

#include "hba/core/types.hpp"

namespace hba {

struct PointCloud {
  std::vector<Vec3f> points;
  std::vector<float> intensity;  // empty, or one value per point
  Vec3 origin = Vec3::Zero();    // metres; zero for scans, may be set for maps

  // Point i in the frame `origin` refers to, in double.
  Vec3 world(std::size_t i) const { return origin + points[i].cast<double>(); }

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasIntensity() const { return !intensity.empty(); }
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
