#pragma once
// Ceres manifold of a PoseBlock whose rotation is held and whose position is
// solved: Plus((t, q), dt) = (t + dt, q). The gauge anchor of a component
// whose priors fix its position but not its orientation.
#include <ceres/manifold.h>

namespace hba::graph {

class OrientationHeldManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace hba::graph
