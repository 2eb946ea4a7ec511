#include "clamped_inverse.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace hba::graph {
namespace {

// The symmetric part of a matrix and the floor its eigenvalues are raised
// to; `raises` when one of them lies below it.
struct Spectrum {
  Eigen::MatrixXd symmetric;
  Eigen::VectorXd values;  // ascending
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
  out.values = spectrum.eigenvalues();
  out.raises = out.values.minCoeff() < out.floor;
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

// A fixed start for the subspace below: the same numbers on every
// platform (std's distributions are not), spread over [-1, 1].
Eigen::MatrixXd startingBlock(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd block(rows, cols);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      block(i, j) = static_cast<double>(state >> 11) / 4503599627370496.0 - 1.0;  // 2^52
    }
  }
  return block;
}

Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& block) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(block);
  return qr.householderQ() * Eigen::MatrixXd::Identity(block.rows(), block.cols());
}

// Extra directions iterated beside those to raise: the subspace converges
// at the ratio of the last raised eigenvalue to the first beyond it.
constexpr Eigen::Index kExtraDirections = 8;
constexpr int kMostIterations = 40;

// The symmetric matrix with its few eigenvalues below the floor raised,
// S + sum (floor - l_i) v_i v_i^T, from those eigenpairs alone: inverse
// iteration on a subspace a little larger than their count, then its
// Rayleigh-Ritz pairs. A window's Hessian of hundreds of rows raises one
// or two; its full eigen-decomposition costs several times this. nullopt where
// they are too many or did not converge (the full decomposition then).
std::optional<Eigen::MatrixXd> raisedFew(const Spectrum& s) {
  const Eigen::Index n = s.symmetric.rows();
  Eigen::Index raised = 0;
  while (raised < n && s.values[raised] < s.floor) ++raised;
  const Eigen::Index m = std::min(n, raised + kExtraDirections);
  if (raised == 0 || 4 * m > n) return std::nullopt;
  // Shifted so that the smallest eigenvalue becomes the floor: positive
  // definite, and the raised directions the largest of its inverse.
  const double shift = s.values[0] - s.floor;
  const Eigen::LLT<Eigen::MatrixXd> factor(s.symmetric - shift * Eigen::MatrixXd::Identity(n, n));
  if (factor.info() != Eigen::Success) return std::nullopt;
  // Converged when each raised pair's residual is a millionth of the floor:
  // its correction is then right to 1e-12 of the largest eigenvalue.
  const double tolerance = 1e-6 * s.floor;
  Eigen::MatrixXd basis = orthonormal(startingBlock(n, m));
  for (int iteration = 0; iteration < kMostIterations; ++iteration) {
    basis = orthonormal(factor.solve(basis));
    const Eigen::MatrixXd projected = basis.transpose() * s.symmetric * basis;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (projected + projected.transpose()));
    if (ritz.info() != Eigen::Success) return std::nullopt;
    const Eigen::MatrixXd vectors = basis * ritz.eigenvectors();
    const Eigen::VectorXd& values = ritz.eigenvalues();
    Eigen::Index below = 0;
    while (below < m && values[below] < s.floor) ++below;
    if (below != raised) continue;
    bool converged = true;
    for (Eigen::Index i = 0; i < raised && converged; ++i) {
      converged = (s.symmetric * vectors.col(i) - values[i] * vectors.col(i)).norm() <= tolerance;
    }
    if (!converged) continue;
    Eigen::MatrixXd out = s.symmetric;
    for (Eigen::Index i = 0; i < raised; ++i)
      out.noalias() += (s.floor - values[i]) * vectors.col(i) * vectors.col(i).transpose();
    if (!out.allFinite()) return std::nullopt;
    return Eigen::MatrixXd(0.5 * (out + out.transpose()));
  }
  return std::nullopt;
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
  if (std::optional<Eigen::MatrixXd> few = raisedFew(*spectrum)) return few;
  return raisedThrough(spectrum->symmetric, spectrum->floor, [](double v) { return v; });
}

}  // namespace hba::graph
