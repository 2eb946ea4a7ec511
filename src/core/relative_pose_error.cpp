#include "hba/core/relative_pose_error.hpp"

#include "hba/core/lie.hpp"

namespace hba {

Vec6 relativePoseError(const Pose& measurement, const Pose& from, const Pose& to) {
  const Pose error_pose = measurement.inverse() * from.inverse() * to;
  Vec6 e;
  e.head<3>() = error_pose.t;
  e.tail<3>() = so3Log(error_pose.q);
  return e;
}

// Derivation (docs/graph.md): with R_E = R_m^T R_a^T R_b,
//   R_b <- Exp(d) R_b  gives R_E Exp(R_b^T d)   -> dLog = J_r^-1 R_b^T d,
//   R_a <- Exp(d) R_a  gives R_E Exp(-R_b^T d)  -> dLog = -J_r^-1 R_b^T d,
// and t_E = R_m^T R_a^T (t_b - t_a) - R_m^T t_m is linear in t_a, t_b, while
// R_a^T <- R_a^T Exp(-d) adds R_m^T R_a^T [t_b - t_a]x d.
RelativePoseErrorJacobians relativePoseErrorJacobians(const Pose& measurement, const Pose& from,
                                                      const Pose& to) {
  RelativePoseErrorJacobians out;
  out.error = relativePoseError(measurement, from, to);

  const Mat3 Rm_t_Ra_t = measurement.R().transpose() * from.R().transpose();
  // J_r^-1(phi) = J_l^-1(-phi).
  const Mat3 rotation_block = so3LeftJacobianInverse(-Vec3(out.error.tail<3>())) * to.R().transpose();

  out.d_from.setZero();
  out.d_from.topLeftCorner<3, 3>() = -Rm_t_Ra_t;
  out.d_from.topRightCorner<3, 3>() = Rm_t_Ra_t * hat(to.t - from.t);
  out.d_from.bottomRightCorner<3, 3>() = -rotation_block;

  out.d_to.setZero();
  out.d_to.topLeftCorner<3, 3>() = Rm_t_Ra_t;
  out.d_to.bottomRightCorner<3, 3>() = rotation_block;
  return out;
}

}  // namespace hba
