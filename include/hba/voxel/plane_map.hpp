#pragma once
// Adaptive voxel plane extraction (BALM / HBA): the scans are put into the
// world with their current poses and hashed into cubic voxels of edge V. A
// voxel whose points pass the plane test is a plane feature; otherwise it is
// split into 8 octants, recursively, down to a depth limit. See docs/ba.md.
#include <cstdint>
#include <utility>
#include <vector>

#include "hba/core/frame_cluster.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::voxel {

struct PlaneSettings {
  double voxel_size = 4.0;    // V, root voxel edge (m)
  double eigen_ratio = 0.05;  // theta: plane if lambda_min / lambda_max < theta
  int max_depth = 3;          // octree splits below the root voxel
  // Fewest points a voxel needs for the plane test. Few points pass it by
  // chance: 10 scattered (foliage-like) points often look planar.
  int min_points = 20;
  // Degeneracy guard beyond the paper's test: a cluster with
  // lambda_min / lambda_mid >= line_ratio is a line (its normal can spin about
  // it) and is not used as a plane.
  double line_ratio = 0.25;
  int min_frames = 2;  // a plane seen by fewer frames constrains nothing
};

// One point of one scan: scans[frame].points[index].
struct PointRef {
  std::uint32_t frame = 0;
  std::uint32_t index = 0;
};

// One plane: what each observing frame's points sum to, in that frame's
// own coordinates (all the cost needs: the extraction is the only pass over
// the points), and where its points sit in the extraction's list of them.
struct PlaneFeature {
  std::vector<FrameCluster> clusters;  // one per observing frame, ascending
  std::uint32_t first_point = 0;       // its points: PlaneExtraction::point_ids
  std::uint32_t end_point = 0;         //   [first_point, end_point)
  int depth = 0;                       // 0 = root voxel, 1 = octant, ...
  std::size_t pointCount() const { return end_point - first_point; }
};

// The planes of one extraction and their points. A point's id counts
// through the scans in order (scans[0]'s points first), so each plane's ids
// ascend by (frame, index).
struct PlaneExtraction {
  std::vector<PlaneFeature> planes;
  std::vector<std::uint32_t> point_ids;  // each plane's ids in one run
  std::vector<std::uint32_t> first_id;   // of each scan, and the total last

  // A plane's points, sorted by (frame, index).
  std::vector<PointRef> pointsOf(const PlaneFeature& plane) const;
  // The indices (ascending) of every plane's points, per scan.
  std::vector<std::vector<std::uint32_t>> pointIndicesPerScan() const;
};

// Plane test on the eigenvalues l1 <= l2 <= l3 of a point covariance.
bool passesPlaneTest(const Vec3& eigenvalues, const PlaneSettings& settings);

// Extracts the plane features of `scans` placed in the world by `poses`.
// The output order is fixed (voxels in lexicographic key order, octants in
// index order) and does not depend on hashing or on the thread count.
// Throws hba::Error if the sizes differ, a scan is null, or settings are invalid.
PlaneExtraction extractPlanes(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                              const PlaneSettings& settings);

// The planes of share `share` (0 .. shares - 1) of the root voxels: ranges
// of their x index, about equal in points, in ascending order. The shares'
// planes, one after the other in share order, are extractPlanes(scans,
// poses, settings)'s, bit for bit: each process of a group can extract
// its own share. Throws as extractPlanes, and for a share >= shares.
PlaneExtraction extractPlanes(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                              const PlaneSettings& settings, std::size_t share, std::size_t shares);

// The planes at two root voxels, `settings.voxel_size` and `fine_voxel`, of
// the same scans at the same poses: the same features, bit for bit, as two
// extractPlanes calls, with the points placed and hashed into cells once
// (the coarse cells are gathered from the fine ones where the ratio is a
// power of two). Throws as extractPlanes, and if fine_voxel is not in
// (0, voxel_size].
std::pair<PlaneExtraction, PlaneExtraction> extractPlanesAtTwoVoxels(
    const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
    const PlaneSettings& settings, double fine_voxel);

}  // namespace hba::voxel
