#include "clamped_inverse.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace hba::graph {
namespace {

// The symmetric part of a matrix and the floor its eigenvalues are raised
// to; `raises` when one of them lies below it.
struct Spectrum {
  Eigen::MatrixXd symmetric;
  double floor = 0.0;
  bool raises = false;
};

std::optional<Spectrum> spectrumOf(const Eigen::MatrixXd& matrix, double min_eigen_ratio) {
  if (matrix.size() == 0 || !matrix.allFinite()) return std::nullopt;
  Spectrum out;
  out.symmetric = 0.5 * (matrix + matrix.transpose());
  // The eigenvalues alone first (a fraction of the cost of the vectors for
  // a window of hundreds of rows): the vectors only where one is raised.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> spectrum(out.symmetric, Eigen::EigenvaluesOnly);
  if (spectrum.info() != Eigen::Success) return std::nullopt;
  const double largest = spectrum.eigenvalues().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::nullopt;
  out.floor = min_eigen_ratio * largest;
  if (!(out.floor > 0.0)) return std::nullopt;  // ratio <= 0, or underflow
  out.raises = spectrum.eigenvalues().minCoeff() < out.floor;
  return out;
}

// V f(max(lambda, floor)) V^T of the eigen-decomposition of `symmetric`.
template <typename OfEigenvalue>
std::optional<Eigen::MatrixXd> raisedThrough(const Eigen::MatrixXd& symmetric, double floor,
                                             const OfEigenvalue& of) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  if (eigen.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd values =
      eigen.eigenvalues().unaryExpr([&](double v) { return of(std::max(v, floor)); });
  const Eigen::MatrixXd& vectors = eigen.eigenvectors();
  Eigen::MatrixXd out = vectors * values.asDiagonal() * vectors.transpose();
  if (!out.allFinite()) return std::nullopt;
  return Eigen::MatrixXd(0.5 * (out + out.transpose()));
}

}  // namespace

std::optional<Eigen::MatrixXd> clampedInverse(const Eigen::MatrixXd& matrix, double min_eigen_ratio) {
  const std::optional<Spectrum> spectrum = spectrumOf(matrix, min_eigen_ratio);
  if (!spectrum) return std::nullopt;
  if (!spectrum->raises) {  // the inverse itself, from a Cholesky factor
    const Eigen::LLT<Eigen::MatrixXd> cholesky(spectrum->symmetric);
    Eigen::MatrixXd inverse = cholesky.solve(Eigen::MatrixXd::Identity(matrix.rows(), matrix.cols()));
    if (cholesky.info() == Eigen::Success && inverse.allFinite())
      return Eigen::MatrixXd(0.5 * (inverse + inverse.transpose()));
  }
  return raisedThrough(spectrum->symmetric, spectrum->floor, [](double v) { return 1.0 / v; });
}

std::optional<Eigen::MatrixXd> clampedUp(const Eigen::MatrixXd& matrix, double min_eigen_ratio) {
  const std::optional<Spectrum> spectrum = spectrumOf(matrix, min_eigen_ratio);
  if (!spectrum) return std::nullopt;
  if (!spectrum->raises) return spectrum->symmetric;
  return raisedThrough(spectrum->symmetric, spectrum->floor, [](double v) { return v; });
}

}  // namespace hba::graph
