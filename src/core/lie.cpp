#include "hba/core/lie.hpp"

#include <cmath>

namespace hba {
namespace {
constexpr double kSmallAngle = 1e-8;
}

Mat3 hat(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Mat3 so3Exp(const Vec3& phi) {
  return Eigen::AngleAxisd(phi.norm(), phi.norm() > 0 ? Vec3(phi.normalized()) : Vec3::UnitX())
      .toRotationMatrix();
}

Vec3 so3Log(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() *= -1.0;  // shortest rotation, angle in [0, pi]
  const double sin_half = q.vec().norm();
  if (sin_half < kSmallAngle) return 2.0 * q.vec();  // first order, w ~ 1
  const double angle = 2.0 * std::atan2(sin_half, q.w());
  return q.vec() * (angle / sin_half);
}

Vec3 so3Log(const Mat3& R) { return so3Log(Quat(R)); }

Mat3 so3LeftJacobian(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 K = hat(phi);
  if (theta < 1e-5) return Mat3::Identity() + 0.5 * K + K * K / 6.0;
  const double t2 = theta * theta;
  return Mat3::Identity() + (1.0 - std::cos(theta)) / t2 * K +
         (theta - std::sin(theta)) / (t2 * theta) * K * K;
}

Mat3 so3LeftJacobianInverse(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 K = hat(phi);
  if (theta < 1e-5) return Mat3::Identity() - 0.5 * K + K * K / 12.0;
  const double t2 = theta * theta;
  const double coeff = 1.0 / t2 - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  return Mat3::Identity() - 0.5 * K + coeff * K * K;
}

Pose se3Exp(const Vec6& xi) {
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  return Pose(so3Exp(phi), Vec3(so3LeftJacobian(phi) * rho));
}

Vec6 se3Log(const Pose& T) {
  const Vec3 phi = so3Log(T.q);
  Vec6 xi;
  xi.head<3>() = so3LeftJacobianInverse(phi) * T.t;
  xi.tail<3>() = phi;
  return xi;
}

}  // namespace hba
