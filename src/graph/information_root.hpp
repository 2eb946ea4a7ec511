#pragma once
// Square roots and checks of information matrices of any fixed size (6x6 for
// relative factors and pose priors, 3x3 for position priors).
#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "hba/core/error.hpp"

namespace hba::graph {

// S with S^T S = information, from the eigen-decomposition of its symmetric
// part, so that a positive semi-definite (singular) information works too.
// Throws hba::Error "<what> is not finite" / "... is not positive
// semi-definite" (round-off negatives are clamped to zero).
template <int N>
Eigen::Matrix<double, N, N> informationRoot(const Eigen::Matrix<double, N, N>& information,
                                            const std::string& what) {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  if (!information.allFinite()) throw Error(what + " is not finite");
  const Matrix symmetric = 0.5 * (information + information.transpose());
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(symmetric);
  const Vector& values = eigen.eigenvalues();
  // Round-off may leave tiny negative eigenvalues; a large one is bad input.
  const double scale = values.cwiseAbs().maxCoeff();
  if (values.minCoeff() < -1e-9 * scale) throw Error(what + " is not positive semi-definite");
  const Vector roots = values.unaryExpr([](double v) { return std::sqrt(std::max(v, 0.0)); });
  return roots.asDiagonal() * eigen.eigenvectors().transpose();
}

// A direction weaker than this fraction of the strongest is taken as
// unconstrained (as InformationSettings::min_eigen_ratio's default does).
inline constexpr double kFirmEigenRatio = 1e-6;

// Whether `information` (finite, positive semi-definite) constrains every
// direction: its smallest eigenvalue is at least kFirmEigenRatio times its
// largest, which is positive.
template <int N>
bool constrainsEveryDirection(const Eigen::Matrix<double, N, N>& information) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const Matrix symmetric = 0.5 * (information + information.transpose());
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(symmetric, Eigen::EigenvaluesOnly);
  const double largest = eigen.eigenvalues().maxCoeff();
  return largest > 0.0 && eigen.eigenvalues().minCoeff() >= kFirmEigenRatio * largest;
}

}  // namespace hba::graph
