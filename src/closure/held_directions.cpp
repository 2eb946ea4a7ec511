#include "held_directions.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace hba::closure {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Eigenvalues below this share of the largest count as no information at all
// (rounding in a Hessian summed over many points).
constexpr double kNoInformation = 1e-12;

struct BlockSpread {
  double worst = 0.0;  // variance
  double best = 0.0;
  Vec3 worst_axis = Vec3::UnitX();
};

BlockSpread spreadOf(const Mat3& covariance) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(covariance);
  BlockSpread s;
  s.best = eigen.eigenvalues()(0);
  s.worst = eigen.eigenvalues()(2);
  s.worst_axis = eigen.eigenvectors().col(2);
  return s;
}

// An eigenvector's sign is arbitrary: report it with its largest component positive.
Vec3 canonicalAxis(const Vec3& v) {
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  return v(largest) < 0.0 ? Vec3(-v) : v;
}

}  // namespace

HeldDirections heldDirections(const Mat6& fisher) {
  HeldDirections held;
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(0.5 * (fisher + fisher.transpose()));
  const double largest = eigen.eigenvalues()(5);
  if (!(largest > 0.0) || !std::isfinite(largest)) {
    held.sigma_m = held.sigma_deg = held.translation_ratio = held.rotation_ratio = kInf;
    return held;
  }
  // A free direction: infinite variance along it, in the part (translation or
  // rotation) it mostly lies in.
  Mat6 covariance = Mat6::Zero();
  bool free_translation = false;
  bool free_rotation = false;
  for (int k = 0; k < 6; ++k) {
    const double lambda = eigen.eigenvalues()(k);
    const Vec6 v = eigen.eigenvectors().col(k);
    if (lambda > kNoInformation * largest) {
      covariance += v * v.transpose() / lambda;
    } else if (v.head<3>().squaredNorm() >= v.tail<3>().squaredNorm()) {
      free_translation = true;
      held.weakest_translation = canonicalAxis(v.head<3>().normalized());
    } else {
      free_rotation = true;
      held.weakest_rotation = canonicalAxis(v.tail<3>().normalized());
    }
  }
  const BlockSpread translation = spreadOf(covariance.topLeftCorner<3, 3>());
  const BlockSpread rotation = spreadOf(covariance.bottomRightCorner<3, 3>());
  if (free_translation || !(translation.best > 0.0)) {
    held.sigma_m = held.translation_ratio = kInf;
  } else {
    held.sigma_m = std::sqrt(translation.worst);
    held.translation_ratio = std::sqrt(translation.worst / translation.best);
    held.weakest_translation = canonicalAxis(translation.worst_axis);
  }
  if (free_rotation || !(rotation.best > 0.0)) {
    held.sigma_deg = held.rotation_ratio = kInf;
  } else {
    held.sigma_deg = std::sqrt(rotation.worst) * 180.0 / M_PI;
    held.rotation_ratio = std::sqrt(rotation.worst / rotation.best);
    held.weakest_rotation = canonicalAxis(rotation.worst_axis);
  }
  return held;
}

}  // namespace hba::closure
