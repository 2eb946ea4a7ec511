#pragma once
// Small helpers shared by the graph tests: random poses, the BA's world-frame
// perturbation, and gauge-invariant synthetic window Hessians.
#include <algorithm>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "hba/core/lie.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/relative_pose_error.hpp"

namespace hba::graph::test {

inline Vec3 randomVec3(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

inline Vec6 randomVec6(std::mt19937& rng, double translation, double rotation) {
  Vec6 xi;
  xi << randomVec3(rng, translation), randomVec3(rng, rotation);
  return xi;
}

inline Pose randomPose(std::mt19937& rng, double translation = 10.0, double rotation = 2.0) {
  return Pose(so3Exp(randomVec3(rng, rotation)), randomVec3(rng, translation));
}

// The BA convention: R <- Exp(dphi) R, t <- t + dt, with delta = (dt, dphi).
inline Pose perturbWorld(const Pose& pose, const Vec6& delta) {
  return Pose(Mat3(so3Exp(delta.tail<3>()) * pose.R()), Vec3(pose.t + delta.head<3>()));
}

// The 6K x 6 basis of one rigid motion of all frames, in world perturbations:
// dt_i = dt + dphi x t_i, dphi_i = dphi. Every window Hessian vanishes on it.
inline Eigen::MatrixXd gaugeBasis(const std::vector<Pose>& poses) {
  Eigen::MatrixXd N(6 * poses.size(), 6);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    auto block = N.middleRows<6>(static_cast<Eigen::Index>(6 * i));
    block.setIdentity();
    block.topRightCorner<3, 3>() = -hat(poses[i].t);
  }
  return N;
}

// The central difference of f(poses) along tangent direction `d` of pose
// `node` (perturbWorld by +-h): (f(ahead) - f(behind)) / 2h.
template <typename F>
auto centralDifference(const std::vector<Pose>& poses, std::size_t node, int d, double h, const F& f) {
  Vec6 step = Vec6::Zero();
  step[d] = h;
  std::vector<Pose> ahead = poses;
  std::vector<Pose> behind = poses;
  ahead[node] = perturbWorld(poses[node], step);
  behind[node] = perturbWorld(poses[node], -step);
  return ((f(ahead) - f(behind)) / (2.0 * h)).eval();
}

// d relativePoseError(measured(a, b), a, b) / d (all window perturbations)
// by central differences, 6 x 6K.
inline Eigen::MatrixXd numericRelativeErrorJacobian(const std::vector<Pose>& poses, std::size_t a,
                                                    std::size_t b) {
  const Pose measurement = relative(poses[a], poses[b]);
  const auto error = [&](const std::vector<Pose>& p) { return relativePoseError(measurement, p[a], p[b]); };
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, 6 * poses.size());
  for (std::size_t frame : {a, b}) {
    for (int k = 0; k < 6; ++k) {
      J.col(static_cast<Eigen::Index>(6 * frame) + k) = centralDifference(poses, frame, k, 1e-6, error);
    }
  }
  return J;
}

// Hessian of the cost sum_pairs e_ab^T W e_ab (a linearized window whose data
// are relative-pose measurements with information W between the listed
// pairs): H = 2 sum J^T W J. Gauge-invariant by construction.
inline Eigen::MatrixXd pairwiseHessian(const std::vector<Pose>& poses,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                                       const Mat6& W) {
  const auto n = static_cast<Eigen::Index>(6 * poses.size());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (const auto& [a, b] : pairs) {
    const auto jac = relativePoseErrorJacobians(relative(poses[a], poses[b]), poses[a], poses[b]);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, n);
    J.middleCols<6>(static_cast<Eigen::Index>(6 * a)) = jac.d_from;
    J.middleCols<6>(static_cast<Eigen::Index>(6 * b)) = jac.d_to;
    H += 2.0 * J.transpose() * W * J;
  }
  return H;
}

// The largest position distance (m) or rotation angle (rad) between the
// poses of `a` and `b`, pairwise.
inline double maxPoseError(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, (a[i].t - b[i].t).norm());
    worst = std::max(worst, a[i].q.angularDistance(b[i].q));
  }
  return worst;
}

}  // namespace hba::graph::test
