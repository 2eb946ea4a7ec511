#pragma once
// Information matrices of relative-pose factors, derived from a BA window's
// Hessian (see docs and DESIGN.md section 4).
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
  // Eigenvalues of the relative-pose covariance are clamped to at least this
  // fraction of the largest one: a degenerate direction gets a weak but
  // finite weight, never an infinite one.
  double min_eigen_ratio = 1e-6;
};

// `hessian` is the 6K x 6K Hessian of a window's BA cost at `poses` in the BA
// convention of hba/ba/window_ba.hpp (R <- Exp(dphi) R, t <- t + dt, rows
// (dt, dphi) per frame), not gauge-fixed. Returns the information matrix of
// the relative pose between window frames a and b, in the pose graph's
// residual tangent.
Mat6 relativePoseInformation(const Eigen::MatrixXd& hessian, const std::vector<Pose>& poses,
                             std::size_t a, std::size_t b,
                             const InformationSettings& settings = {});

}  // namespace hba::graph
