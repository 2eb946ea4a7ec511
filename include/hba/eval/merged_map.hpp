#pragma once
// The merged map of a sequence: every scan moved into the world by its pose,
// voxel-downsampled as it streams in (only one raw scan is in memory at a
// time; the map holds one accumulator per occupied voxel).
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/memory_budget.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/voxel/key_table.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::eval {

// Which point represents a voxel.
enum class VoxelRule {
  Centroid,   // the mean of the voxel's points (PCL VoxelGrid's and voxel::downsample's rule)
  FirstPoint  // the first point that fell into the voxel, in scan order
};

// What the output cloud's intensity field carries (the io writers store
// x y z intensity only, so a colour cue travels there).
enum class MapColor {
  None,   // the mean input intensity of the voxel (none if the scans have none)
  Scan,   // the index of the first scan that touched the voxel
  Height  // the point's z in metres
};

struct MapSettings {
  double voxel = 0.1;  // m; <= 0 keeps every point
  VoxelRule rule = VoxelRule::Centroid;
  MapColor color = MapColor::None;
  // buildMergedMap stops (MemoryExceeded) once the process outgrows it:
  // how much the scans overlap, and so the map's size, is known only at
  // the end. No limit by default.
  MemoryBudget budget;
};

// Accumulates world points voxel by voxel. Output order is the order in
// which voxels were first touched, so results are deterministic. The grid is
// the world's; the output's points are stored relative to `origin` (its
// PointCloud::origin), so maps far from the world origin keep their precision.
class VoxelMerger {
 public:
  explicit VoxelMerger(const MapSettings& settings, const Vec3& origin = Vec3::Zero());
  // Adds `scan` (sensor frame, or relative to scan.origin) moved into the world by `pose`.
  void add(const PointCloud& scan, const Pose& pose, std::uint32_t scan_index);
  std::size_t voxelCount() const { return cells_.size(); }
  PointCloud result() const;
  // The index of the first scan that touched each of result()'s points, in its order.
  std::vector<std::uint32_t> firstScans() const;

 private:
  struct Cell {
    Vec3 sum = Vec3::Zero();
    Vec3f first = Vec3f::Zero();
    double intensity_sum = 0.0;
    std::uint32_t count = 0;
    std::uint32_t first_scan = 0;
  };
  MapSettings settings_;
  Vec3 origin_;
  bool has_intensity_ = true;  // false once a scan without intensity arrives
  // The grid of hba::voxel::downsample, so both agree on what a voxel is.
  voxel::VoxelIndex index_;  // key -> cells_ slot
  std::vector<Cell> cells_;
};

// Streams every scan of `scans` through a VoxelMerger with `poses` (one per
// scan). When the first scan lies more than 10 km out (its pose's position,
// or its own origin moved by that pose: world points in UTM), the map's
// points are relative to that place (the map's `origin`). When `first_scans` is
// given, it receives each map point's first scan index (the LAS writer
// stores it whatever --color says). Throws hba::Error, and MemoryExceeded
// when the map outgrows settings.budget.
PointCloud buildMergedMap(const io::ScanSource& scans, const std::vector<Pose>& poses,
                          const MapSettings& settings, std::vector<std::uint32_t>* first_scans = nullptr);

// Downsamples a cloud that is already in the world frame (a map file).
PointCloud downsampleMap(const PointCloud& cloud, const MapSettings& settings);

}  // namespace hba::eval

namespace hba {
template <>
struct EnumNames<eval::MapColor> {
  static constexpr const char* what = "map colour";
  static constexpr EnumName<eval::MapColor> names[] = {
      {eval::MapColor::None, "none"}, {eval::MapColor::Scan, "scan"}, {eval::MapColor::Height, "height"}};
};
}  // namespace hba
