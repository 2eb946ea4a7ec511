#pragma once
// The self-check of hba optimize: how crisp the map is with given poses,
// measured on one fixed set of planes (found at the input poses, finest
// voxel) so that the input, the hierarchy's and the final poses are
// compared like for like; in total and per stretch of the trajectory.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "hba/ba/association.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"

namespace hba::refine {

class FixedPlaneMap {
 public:
  // The planes of `found`, an association over `frames` frames (at the
  // input poses, with the refinement's plane settings).
  FixedPlaneMap(const ba::PlaneProblem& found, std::size_t frames, std::size_t regions);

  // When `found` is spread over a group's processes, the map is too: each
  // holds its planes, and the figures (collectives) are of every plane.
  std::size_t planes() const { return plane_points_.size(); }
  std::size_t regions() const { return region_points_.size(); }
  double points() const { return points_; }
  // RMS point-to-plane distance (m) over all planes, and per region (planes
  // belong to the region of their first observing frame; a region without
  // planes reads 0).
  double rms(const std::vector<Pose>& poses) const;
  std::vector<double> regionRms(const std::vector<Pose>& poses) const;
  // Both from one evaluation of the planes (the same figures).
  struct Figures {
    double rms = 0.0;
    std::vector<double> region_rms;
  };
  Figures figures(const std::vector<Pose>& poses) const;
  // First frame of each region.
  const std::vector<std::size_t>& regionStarts() const { return region_starts_; }
  // The map written to a file and read back, the same to the bit (a
  // long refinement keeps its blocks' maps on disk, not in memory); a
  // spread map is each member's part, read back with its `group`.
  // Throw hba::Error naming the file.
  void save(const std::filesystem::path& path) const;
  static FixedPlaneMap load(const std::filesystem::path& path, const dist::Group* group = nullptr);
  const dist::Group* group() const { return group_; }

 private:
  // A frame's cluster of one plane in single precision (44 bytes instead
  // of 112): the map is held beside the refinement's own plane problem and
  // only compared with itself under two sets of poses.
  struct CompactCluster {
    std::uint32_t frame = 0;
    float count = 0.0f;
    std::array<float, 3> mean{};     // plain floats: the map is written to disk as bytes
    std::array<float, 6> scatter{};  // xx xy xz yy yz zz
  };
  FixedPlaneMap() = default;
  std::vector<double> planeCosts(const std::vector<Pose>& poses) const;
  double rmsOf(const std::vector<double>& costs) const;
  std::vector<double> regionRmsOf(const std::vector<double>& costs) const;

  std::vector<CompactCluster> clusters_;
  std::vector<std::size_t> plane_begin_{0};  // clusters of plane p: [plane_begin_[p], plane_begin_[p+1])
  std::vector<std::size_t> plane_region_;
  std::vector<double> plane_points_;
  std::vector<double> region_points_;
  std::vector<std::size_t> region_starts_;
  double points_ = 0.0;
  const dist::Group* group_ = nullptr;  // spread over it; null: one process
};

}  // namespace hba::refine
