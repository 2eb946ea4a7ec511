#pragma once
// SO(3) and SE(3) exponential and logarithm maps.
//
// Tangent vectors of SE(3) are ordered translation first: xi = (rho, phi),
// rho in R^3 the translational part and phi in R^3 the rotation vector.
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba {

// Skew-symmetric matrix [v]x such that [v]x w = v x w.
Mat3 hat(const Vec3& v);

Mat3 so3Exp(const Vec3& phi);
Vec3 so3Log(const Mat3& R);
Vec3 so3Log(const Quat& q);
// Left Jacobian of SO(3) and its inverse (J_l(phi) = J_r(-phi)).
Mat3 so3LeftJacobian(const Vec3& phi);
Mat3 so3LeftJacobianInverse(const Vec3& phi);

Pose se3Exp(const Vec6& xi);
Vec6 se3Log(const Pose& T);

}  // namespace hba
