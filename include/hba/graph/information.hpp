#pragma once
// Information matrices of relative-pose factors, derived from a BA window's
// Hessian (see docs/graph.md and DESIGN.md section 4).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

struct InformationSettings {
  // Standard deviation of the point-to-plane noise (m): the BA cost is a sum
  // of squared distances, so the Fisher information is H / (2 sigma^2).
  double point_sigma = 0.02;
  // Eigenvalues of the gauge-fixed Fisher information, and then of the
  // relative-pose covariance, are clamped to at least this fraction of the
  // largest one: a degenerate direction (a corridor, an open field) gets a
  // weak but finite weight, never an infinite one. In (0, 1].
  double min_eigen_ratio = 1e-6;
  // Isotropic information returned when the Hessian carries none at all (a
  // window without plane features): the factor then barely holds the pose.
  double fallback_information = 1e-6;
};

// `hessian` is the 6K x 6K Hessian of a window's BA cost at `poses` in the BA
// convention of hba/ba/window_ba.hpp (R <- Exp(dphi) R, t <- t + dt, rows
// (dt, dphi) per frame), not gauge-fixed. Returns the information matrix of
// the relative pose between window frames a and b, in the tangent of the
// residual of hba/core/relative_pose_error.hpp: the gauge is fixed by
// holding the window's first frame (as the BA does; the relative pose is
// gauge-invariant, so any frame gives the same covariance), the covariance of
// frames a and b is propagated through the residual's Jacobians, and the
// result is inverted (symmetric, positive definite). Throws hba::Error on a == b, an index out of range, a
// Hessian of the wrong size or with non-finite entries, or invalid settings.
Mat6 relativePoseInformation(const Eigen::MatrixXd& hessian, const std::vector<Pose>& poses, std::size_t a,
                             std::size_t b, const InformationSettings& settings = {});

}  // namespace hba::graph
