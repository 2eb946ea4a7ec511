#pragma once
// A pose as one Ceres parameter block: [tx ty tz qx qy qz qw].
#include <array>

#include "hba/core/pose.hpp"

namespace hba::graph {

using PoseBlock = std::array<double, 7>;

inline PoseBlock toPoseBlock(const Pose& pose) {
  return {pose.t.x(), pose.t.y(), pose.t.z(), pose.q.x(), pose.q.y(), pose.q.z(), pose.q.w()};
}

inline Pose poseFromBlock(const double* block) {
  return Pose(Quat(block[6], block[3], block[4], block[5]), Vec3(block[0], block[1], block[2]));
}

}  // namespace hba::graph
