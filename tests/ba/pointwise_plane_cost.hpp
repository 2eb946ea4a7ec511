#pragma once
// Reference: the plane cost, gradient and Hessian of plane_cost.hpp computed
// the naive way, from every raw point at every evaluation. Used to check the
// cluster form and to measure what clusters save (bench/ba).
#include <vector>

#include <Eigen/Core>

#include "hba/core/pose.hpp"

namespace hba::test {

struct PointwiseResult {
  double cost = 0.0;
  Eigen::VectorXd gradient;  // 6F, coordinates (dt, dphi) per observing frame
  Eigen::MatrixXd hessian;   // 6F x 6F
};

// points[a] are the sensor points of the plane seen by frame `poses[a]`.
PointwiseResult pointwisePlaneDerivatives(const std::vector<std::vector<Vec3>>& points,
                                          const std::vector<Pose>& poses);

}  // namespace hba::test
