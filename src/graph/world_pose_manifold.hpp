#pragma once
// Ceres manifold of a PoseBlock with the BA's world-frame perturbation:
// Plus((t, q), (dt, dphi)) = (t + dt, Exp(dphi) q). Using the same tangent
// as the BA Hessian keeps one convention across the library.
#include <ceres/manifold.h>

#include "hba/core/types.hpp"

namespace hba::graph {

class WorldPoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// d(Exp(dphi) q)/d dphi at dphi = 0, rows (qx qy qz qw). Its columns are
// orthogonal with norm 1/2, so 4 * its transpose is its left inverse.
Eigen::Matrix<double, 4, 3> quaternionPlusJacobian(const Quat& q);

// The 6x7 left inverse of PlusJacobian (= MinusJacobian): maps a Jacobian
// w.r.t. the tangent (dt, dphi) to one w.r.t. the block's 7 numbers whose
// product with PlusJacobian is the tangent Jacobian again.
Eigen::Matrix<double, 6, 7> tangentToAmbient(const Quat& q);

}  // namespace hba::graph
