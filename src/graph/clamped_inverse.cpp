#include "clamped_inverse.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace hba::graph {

std::optional<Eigen::MatrixXd> clampedInverse(const Eigen::MatrixXd& matrix, double min_eigen_ratio) {
  if (matrix.size() == 0 || !matrix.allFinite()) return std::nullopt;
  const Eigen::MatrixXd symmetric = 0.5 * (matrix + matrix.transpose());
  // The eigenvalues alone first (a fraction of the cost of the vectors for
  // a window of hundreds of rows): where none is raised, the clamped
  // inverse is the inverse, and a Cholesky factor gives it.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> spectrum(symmetric, Eigen::EigenvaluesOnly);
  if (spectrum.info() != Eigen::Success) return std::nullopt;
  const double largest = spectrum.eigenvalues().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::nullopt;
  const double floor = min_eigen_ratio * largest;
  if (!(floor > 0.0)) return std::nullopt;  // ratio <= 0, or underflow
  if (spectrum.eigenvalues().minCoeff() >= floor) {
    const Eigen::LLT<Eigen::MatrixXd> cholesky(symmetric);
    Eigen::MatrixXd inverse = cholesky.solve(Eigen::MatrixXd::Identity(matrix.rows(), matrix.cols()));
    if (cholesky.info() == Eigen::Success && inverse.allFinite())
      return Eigen::MatrixXd(0.5 * (inverse + inverse.transpose()));
  }

  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  if (eigen.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd& values = eigen.eigenvalues();  // ascending

  const Eigen::VectorXd inverse_values =
      values.unaryExpr([floor](double v) { return 1.0 / std::max(v, floor); });
  const Eigen::MatrixXd& vectors = eigen.eigenvectors();
  Eigen::MatrixXd inverse = vectors * inverse_values.asDiagonal() * vectors.transpose();
  if (!inverse.allFinite()) return std::nullopt;
  return Eigen::MatrixXd(0.5 * (inverse + inverse.transpose()));
}

}  // namespace hba::graph
