#pragma once
// What the scan writers read of a cloud of either kind (PointCloud: floats
// relative to an origin; WideCloud: doubles): each point in double, or as
// the float it is when the file may store floats, and the intensities.
#include <cstddef>
#include <filesystem>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/io/las.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::io::detail {

class CloudView {
 public:
  explicit CloudView(const PointCloud& cloud);
  explicit CloudView(const WideCloud& cloud);

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool hasIntensity() const { return !intensity_.empty(); }
  float intensity(std::size_t i) const { return intensity_[i]; }
  // A raw sweep's point times (PointCloud::time), written by the PCD writer only.
  bool hasTime() const { return time_ != nullptr && !time_->empty(); }
  double time(std::size_t i) const { return (*time_)[i]; }
  // True when some coordinate needs float64 to be kept: a PointCloud with
  // an origin, a WideCloud with a value that is not exactly a float.
  bool wide() const { return wide_; }
  Vec3 world(std::size_t i) const { return narrow_ ? origin_ + narrow_[i].cast<double>() : wide_points_[i]; }
  // Point i as a float, exact when !wide().
  Vec3f point(std::size_t i) const { return narrow_ ? narrow_[i] : wide_points_[i].cast<float>(); }

  // Refuses (hba::Error naming `path`) an intensity or time vector that is
  // neither empty nor one per point: it would be written misaligned.
  void requireOneValuePerPoint(const std::filesystem::path& path) const;

 private:
  std::size_t size_ = 0;
  const Vec3f* narrow_ = nullptr;
  const Vec3* wide_points_ = nullptr;
  Vec3 origin_ = Vec3::Zero();
  const std::vector<float>& intensity_;
  const std::vector<double>* time_ = nullptr;
  bool wide_ = false;
};

// The writers of each format, for either kind of cloud.
void writePcdView(const std::filesystem::path& path, const CloudView& cloud, PcdEncoding encoding);
void writePlyView(const std::filesystem::path& path, const CloudView& cloud, PlyEncoding encoding);
void writeKittiBinView(const std::filesystem::path& path, const CloudView& cloud);
void writeLasView(const std::filesystem::path& path, const CloudView& cloud, const LasPointExtras& extras);

}  // namespace hba::io::detail
