#pragma once
// A cloud with double coordinates, as a file stores them: for programs that
// hand hba world coordinates and want every bit back (the Python module).
// hba's own PointCloud keeps floats relative to an origin, which holds a map
// to a float step of its extent (tens of micrometres over a kilometre), not
// to the last bit of a float64 or the 1e-7 scale of a LAS file in degrees.
#include <cstddef>
#include <filesystem>
#include <vector>

#include "hba/core/types.hpp"

namespace hba::io {

struct WideCloud {
  std::vector<Vec3> points;
  std::vector<float> intensity;  // empty, or one value per point

  Vec3 world(std::size_t i) const { return points[i]; }
  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasIntensity() const { return !intensity.empty(); }
  void reserve(std::size_t n, bool with_intensity) {
    points.reserve(n);
    if (with_intensity) intensity.reserve(n);
  }
  // Appends a point. Use one overload for a whole cloud: with intensity or without.
  void add(const Vec3& p) { points.push_back(p); }
  void add(const Vec3& p, float value) {
    points.push_back(p);
    intensity.push_back(value);
  }
};

// The origin a cloud of these points keeps its float precision by (its
// PointCloud::origin, points stored relative to it): the per-axis median of
// the finite points, in whole metres, when it lies more than 10 km out (a map
// in UTM or ECEF), where floats would round to decimetres; zero nearer, or
// beyond 1e8 m (stray values, not a place). The float64 readers choose a
// file's origin so; neither a stray point nor (0,0,0) placeholders decide it.
Vec3 farCloudOrigin(const std::vector<Vec3>& points);

// The formats and checks of readScan, each coordinate as the file stores it:
// float64 fields and LAS's scaled integers exactly, float32 ones widened.
// NaN/Inf points are dropped. Throws hba::Error.
WideCloud readScanWide(const std::filesystem::path& path);

// The formats of writeScan, keeping every coordinate: .pcd and .ply get
// float64 x y z when one is not exactly a float32 (float32 otherwise, as
// writeScan), .las stores millimetres (the format's integers), .bin (float32
// only) refuses coordinates a float32 would round. Throws hba::Error.
void writeScanWide(const std::filesystem::path& path, const WideCloud& cloud);

}  // namespace hba::io
