#pragma once
// Short names for the Eigen types used throughout hba.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hba {

using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Quat = Eigen::Quaterniond;

}  // namespace hba
