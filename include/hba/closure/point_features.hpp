#pragma once
// Descriptors of local geometry that do not change when the cloud moves:
// surface normals and Fast Point Feature Histograms (Rusu, Blodow and Beetz,
// ICRA 2009). Two clouds of one place, seen from unrelated frames, are
// matched by these descriptors before anything is known of their relative pose.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hba/core/point_cloud.hpp"

namespace hba::closure {

using Fpfh = Eigen::Matrix<float, 33, 1>;  // three histograms of 11 bins, each summing to 100

struct FeatureCloud {
  std::vector<Vec3f> points;
  std::vector<Vec3f> normals;  // unit, of either sign: descriptors do not depend on it
  // Descriptors of a sparser subset (one point per cell of twice the voxel):
  // neighbouring descriptors are alike, and matching costs grow with their number.
  std::vector<std::uint32_t> keypoints;  // indices into points
  std::vector<Fpfh> features;            // one per keypoint
  double voxel = 0.0;                    // the points' spacing (m); radii below are in its units
};

struct FeatureSettings {
  double normal_radius = 2.5;      // voxels: neighbours that fit a point's plane
  double feature_radius = 5.0;     // voxels: neighbours that describe a point
  std::size_t min_neighbours = 5;  // fewer within the normal radius: the point is dropped
  double keypoint_voxels = 3.0;    // keypoints: one per cell of this many voxels
};

// The cloud downsampled to `voxel` (m), its normals and descriptors. Points
// whose neighbourhood is too sparse for a normal are left out. Deterministic.
FeatureCloud describeCloud(const PointCloud& cloud, double voxel, const FeatureSettings& settings = {});

}  // namespace hba::closure
