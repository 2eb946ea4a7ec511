#include "relative_pose_cost.hpp"

#include "hba/core/relative_pose_error.hpp"
#include "information_root.hpp"
#include "pose_block.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {

Mat6 squareRootInformation(const Mat6& information) {
  return informationRoot<6>(information, "pose graph: factor information");
}

RelativePoseCost::RelativePoseCost(const Pose& measurement, const Mat6& sqrt_information)
    : measurement_(measurement), sqrt_information_(sqrt_information) {}

bool RelativePoseCost::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  const Pose from = poseFromBlock(parameters[0]);
  const Pose to = poseFromBlock(parameters[1]);
  Eigen::Map<Vec6> residual(residuals);
  if (!jacobians) {
    residual = sqrt_information_ * relativePoseError(measurement_, from, to);
    return true;
  }
  const RelativePoseErrorJacobians e = relativePoseErrorJacobians(measurement_, from, to);
  residual = sqrt_information_ * e.error;

  using Jacobian = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;
  // Ceres wants Jacobians w.r.t. the 7 block numbers; it multiplies them by
  // the manifold's PlusJacobian, which tangentToAmbient undoes exactly.
  if (jacobians[0]) {
    Eigen::Map<Jacobian> d_from(jacobians[0]);
    d_from = sqrt_information_ * e.d_from * tangentToAmbient(from.q);
  }
  if (jacobians[1]) {
    Eigen::Map<Jacobian> d_to(jacobians[1]);
    d_to = sqrt_information_ * e.d_to * tangentToAmbient(to.q);
  }
  return true;
}

}  // namespace hba::graph
