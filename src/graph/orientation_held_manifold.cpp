#include "orientation_held_manifold.hpp"

#include <Eigen/Core>

namespace hba::graph {

// The costs' ambient Jacobians are the tangent ones times tangentToAmbient,
// whose translation columns are [I; 0]: times PlusJacobian = [I; 0] below,
// Ceres gets exactly the translation columns of the tangent Jacobian.
bool OrientationHeldManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  for (int k = 0; k < 3; ++k) x_plus_delta[k] = x[k] + delta[k];
  for (int k = 3; k < 7; ++k) x_plus_delta[k] = x[k];
  return true;
}

bool OrientationHeldManifold::PlusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 3, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.topRows<3>().setIdentity();
  return true;
}

bool OrientationHeldManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  for (int k = 0; k < 3; ++k) y_minus_x[k] = y[k] - x[k];
  return true;
}

bool OrientationHeldManifold::MinusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.leftCols<3>().setIdentity();
  return true;
}

}  // namespace hba::graph
