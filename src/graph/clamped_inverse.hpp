#pragma once
// Robust inversion of symmetric positive semi-definite matrices (Hessians,
// covariances) that may be singular or slightly indefinite from round-off.
#include <optional>

#include <Eigen/Core>

namespace hba::graph {

// Inverse of the symmetric part of `matrix` after raising every eigenvalue to
// at least `min_eigen_ratio` times the largest one, so that a direction the
// data does not constrain becomes weak but finite. nullopt when the largest
// eigenvalue is not positive (no information at all) or not finite.
std::optional<Eigen::MatrixXd> clampedInverse(const Eigen::MatrixXd& matrix, double min_eigen_ratio);

// The same symmetric part with the same eigenvalues raised, not inverted:
// clampedInverse(m) is its inverse. nullopt where clampedInverse is.
std::optional<Eigen::MatrixXd> clampedUp(const Eigen::MatrixXd& matrix, double min_eigen_ratio);

}  // namespace hba::graph
