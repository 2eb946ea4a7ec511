// Priors on one node's full pose: the relative-pose residual from the world
// origin, so they share its tested Jacobians.
#include <ceres/sized_cost_function.h>

#include "factor_model.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "information_root.hpp"
#include "pose_block.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

const Pose kWorldOrigin;

class PosePriorCost final : public ceres::SizedCostFunction<6, 7> {
 public:
  PosePriorCost(const Pose& measurement, const Mat6& sqrt_information)
      : measurement_(measurement), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Pose pose = poseFromBlock(parameters[0]);
    Eigen::Map<Vec6> residual(residuals);
    if (!jacobians || !jacobians[0]) {
      residual = sqrt_information_ * relativePoseError(measurement_, kWorldOrigin, pose);
      return true;
    }
    const RelativePoseErrorJacobians e = relativePoseErrorJacobians(measurement_, kWorldOrigin, pose);
    residual = sqrt_information_ * e.error;
    // As in RelativePoseCost: tangentToAmbient undoes the manifold's lift.
    Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> d_pose(jacobians[0]);
    d_pose = sqrt_information_ * e.d_to * tangentToAmbient(pose.q);
    return true;
  }

 private:
  Pose measurement_;
  Mat6 sqrt_information_;
};

class PosePriorModel final : public FactorModel {
 public:
  explicit PosePriorModel(const PosePriorFactor& f) : f_(f) {}

  const char* name() const override { return "pose prior"; }
  std::vector<std::size_t> nodes() const override { return {f_.node}; }
  LossGroup lossGroup() const override { return LossGroup::Prior; }
  GaugePin gaugePin() const override {
    GaugePin pin;
    if (constrainsEveryDirection<6>(f_.information)) pin.kind = PinKind::Pose;
    return pin;
  }

  void validate(std::size_t num_poses, const std::string& label) const override {
    checkNode(f_.node, num_poses, label);
    checkFinite(f_.measurement, label);
    informationRoot<6>(f_.information, label + ": information");
  }
  double cost(const std::vector<Pose>& poses) const override {
    const Vec6 e = relativePoseError(f_.measurement, kWorldOrigin, poses[f_.node]);
    return e.dot(f_.information * e);
  }
  ceres::CostFunction* newCost() const override {
    return new PosePriorCost(f_.measurement, informationRoot<6>(f_.information, "pose prior information"));
  }

 private:
  PosePriorFactor f_;
};

}  // namespace

FactorModelPtr modelOf(const PosePriorFactor& factor) {
  return std::make_shared<const PosePriorModel>(factor);
}

}  // namespace hba::graph
