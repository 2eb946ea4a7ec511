// Priors on one node's world position (GNSS in a local metric frame): the
// residual t - position is linear, so its Jacobian is constant.
#include <ceres/sized_cost_function.h>

#include "factor_model.hpp"
#include "hba/core/error.hpp"
#include "information_root.hpp"

namespace hba::graph {
namespace {

class PositionPriorCost final : public ceres::SizedCostFunction<3, 7> {
 public:
  PositionPriorCost(const Vec3& position, const Mat3& sqrt_information)
      : position_(position), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Vec3> t(parameters[0]);
    Eigen::Map<Vec3> residual(residuals);
    residual = sqrt_information_ * (t - position_);
    if (jacobians && jacobians[0]) {
      // The translation rows of tangentToAmbient are [I 0]: the block's
      // quaternion numbers do not enter.
      Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> d_pose(jacobians[0]);
      d_pose.setZero();
      d_pose.leftCols<3>() = sqrt_information_;
    }
    return true;
  }

 private:
  Vec3 position_;
  Mat3 sqrt_information_;
};

class PositionPriorModel final : public FactorModel {
 public:
  explicit PositionPriorModel(const PositionPriorFactor& f) : f_(f) {}

  const char* name() const override { return "position prior"; }
  std::vector<std::size_t> nodes() const override { return {f_.node}; }
  LossGroup lossGroup() const override { return LossGroup::Prior; }
  GaugePin gaugePin() const override {
    GaugePin pin;
    if (constrainsEveryDirection<3>(f_.information)) pin = {PinKind::Position, f_.position};
    return pin;
  }

  void validate(std::size_t num_poses, const std::string& label) const override {
    checkNode(f_.node, num_poses, label);
    if (!f_.position.allFinite()) throw Error(label + " has a non-finite position");
    informationRoot<3>(f_.information, label + ": information");
  }
  double cost(const std::vector<Pose>& poses) const override {
    const Vec3 e = poses[f_.node].t - f_.position;
    return e.dot(f_.information * e);
  }
  ceres::CostFunction* newCost() const override {
    return new PositionPriorCost(f_.position,
                                 informationRoot<3>(f_.information, "position prior information"));
  }

 private:
  PositionPriorFactor f_;
};

}  // namespace

FactorModelPtr modelOf(const PositionPriorFactor& factor) {
  return std::make_shared<const PositionPriorModel>(factor);
}

}  // namespace hba::graph
