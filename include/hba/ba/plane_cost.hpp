#pragma once
// Cost of one plane feature and its exact first and second derivatives, from
// the per-frame point clusters only (no per-point work). See docs/ba.md.
//
// Perturbation of frame i (as in window_ba.hpp): R_i <- Exp(dphi_i) R_i,
// t_i <- t_i + dt_i, coordinates (dt_i, dphi_i).
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hba/core/frame_cluster.hpp"
#include "hba/core/point_cluster.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::ba {

using hba::FrameCluster;
using hba::PointCluster;

// One plane feature: its clusters, one per observing frame, sorted by frame.
struct PlaneObservation {
  std::vector<FrameCluster> clusters;
  double pointCount() const;
};

// Rotation matrices and translations of all frames, computed once per
// evaluation instead of once per plane.
struct FrameTransforms {
  std::vector<Mat3> R;
  std::vector<Vec3> t;
  explicit FrameTransforms(const std::vector<Pose>& poses);
};

// World-frame scatter matrix A = sum over points of (q - mu)(q - mu)^T, so
// that the plane cost is lambda_min(A) = N * lambda_min(C).
Mat3 planeScatter(const PlaneObservation& plane, const FrameTransforms& frames);

// N * lambda_min(C): the sum of squared distances to the best-fit plane.
double planeCost(const PlaneObservation& plane, const FrameTransforms& frames);

// Derivatives of one plane's cost over its F observing frames (local
// coordinates 6a .. 6a+5 for clusters[a]). The local Hessian is
//   H = Z^T diag(weights) Z + blockdiag(diagonal[0..F-1]),
// kept factored so that assembling a plane seen by many frames costs only
// rank-3 products per frame pair.
struct PlaneLinearization {
  double cost = 0.0;
  Eigen::VectorXd gradient;                    // 6F
  Eigen::Matrix<double, 3, Eigen::Dynamic> Z;  // 3 x 6F
  Vec3 weights = Vec3::Zero();
  std::vector<Mat6, Eigen::aligned_allocator<Mat6>> diagonal;  // F blocks 6x6

  Eigen::MatrixXd denseHessian() const;  // 6F x 6F, for tests and small problems
};

PlaneLinearization linearizePlane(const PlaneObservation& plane, const FrameTransforms& frames);

// The same derivatives per cluster a, in storage that is reused from plane
// to plane (no allocation once it has grown): gradient[a] and diagonal[a]
// as above, z[a] the 3x6 columns 6a .. 6a+5 of Z.
struct PlaneTerms {
  double cost = 0.0;
  Vec3 weights = Vec3::Zero();
  std::vector<Vec6, Eigen::aligned_allocator<Vec6>> gradient;
  std::vector<Eigen::Matrix<double, 3, 6>, Eigen::aligned_allocator<Eigen::Matrix<double, 3, 6>>> z;
  std::vector<Mat6, Eigen::aligned_allocator<Mat6>> diagonal;
};
void planeTerms(const PlaneObservation& plane, const FrameTransforms& frames, PlaneTerms& terms);

}  // namespace hba::ba
