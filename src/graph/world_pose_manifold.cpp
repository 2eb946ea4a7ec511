#include "world_pose_manifold.hpp"

#include "hba/core/lie.hpp"

namespace hba::graph {
namespace {
using RowMajor7x6 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;
using RowMajor6x7 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;

Quat blockQuat(const double* x) { return Quat(x[6], x[3], x[4], x[5]).normalized(); }
}  // namespace

Eigen::Matrix<double, 4, 3> quaternionPlusJacobian(const Quat& q) {
  // Exp(d) q ~ (1, d/2) * q, whose vector part gains (q_w d + d x q_v)/2 and
  // whose scalar part gains -q_v.d/2.
  Eigen::Matrix<double, 4, 3> J;
  J.topRows<3>() = 0.5 * (q.w() * Mat3::Identity() - hat(q.vec()));
  J.bottomRows<1>() = -0.5 * q.vec().transpose();
  return J;
}

Eigen::Matrix<double, 6, 7> tangentToAmbient(const Quat& q) {
  Eigen::Matrix<double, 6, 7> M = Eigen::Matrix<double, 6, 7>::Zero();
  M.topLeftCorner<3, 3>().setIdentity();
  M.bottomRightCorner<3, 4>() = 4.0 * quaternionPlusJacobian(q).transpose();
  return M;
}

bool WorldPoseManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Eigen::Map<const Vec3> dt(delta);
  const Eigen::Map<const Vec3> dphi(delta + 3);
  const Quat rotated = (Quat(so3Exp(dphi)) * blockQuat(x)).normalized();
  for (int k = 0; k < 3; ++k) x_plus_delta[k] = x[k] + dt[k];
  x_plus_delta[3] = rotated.x();
  x_plus_delta[4] = rotated.y();
  x_plus_delta[5] = rotated.z();
  x_plus_delta[6] = rotated.w();
  return true;
}

bool WorldPoseManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<RowMajor7x6> J(jacobian);
  J.setZero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.bottomRightCorner<4, 3>() = quaternionPlusJacobian(blockQuat(x));
  return true;
}

bool WorldPoseManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  Eigen::Map<Vec6> out(y_minus_x);
  for (int k = 0; k < 3; ++k) out[k] = y[k] - x[k];
  out.tail<3>() = so3Log(Quat(blockQuat(y) * blockQuat(x).conjugate()));
  return true;
}

bool WorldPoseManifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<RowMajor6x7> J(jacobian);
  J = tangentToAmbient(blockQuat(x));
  return true;
}

}  // namespace hba::graph
