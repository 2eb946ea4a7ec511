// Priors on one node's height in the world frame (a barometer, a floor
// known to be level): the residual z - height is linear, so its Jacobian is
// constant.
#include <ceres/sized_cost_function.h>

#include <cmath>

#include "factor_model.hpp"
#include "hba/core/error.hpp"

namespace hba::graph {
namespace {

class HeightPriorCost final : public ceres::SizedCostFunction<1, 7> {
 public:
  HeightPriorCost(double height, double sqrt_information)
      : height_(height), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    residuals[0] = sqrt_information_ * (parameters[0][2] - height_);
    if (jacobians && jacobians[0]) {
      // Only the block's z enters (its translation comes first).
      for (int k = 0; k < 7; ++k) jacobians[0][k] = 0.0;
      jacobians[0][2] = sqrt_information_;
    }
    return true;
  }

 private:
  double height_;
  double sqrt_information_;
};

class HeightPriorModel final : public FactorModel {
 public:
  explicit HeightPriorModel(const HeightPriorFactor& f) : f_(f) {}

  const char* name() const override { return "height prior"; }
  std::vector<std::size_t> nodes() const override { return {f_.node}; }
  LossGroup lossGroup() const override { return LossGroup::Prior; }

  void validate(std::size_t num_poses, const std::string& label) const override {
    checkNode(f_.node, num_poses, label);
    if (!std::isfinite(f_.height)) throw Error(label + " has a non-finite height");
    if (!(f_.information >= 0.0) || !std::isfinite(f_.information)) {
      throw Error(label + ": information must be finite and not negative");
    }
  }
  double cost(const std::vector<Pose>& poses) const override {
    const double e = poses[f_.node].t.z() - f_.height;
    return f_.information * e * e;
  }
  ceres::CostFunction* newCost() const override {
    return new HeightPriorCost(f_.height, std::sqrt(f_.information));
  }

 private:
  HeightPriorFactor f_;
};

}  // namespace

FactorModelPtr modelOf(const HeightPriorFactor& factor) {
  return std::make_shared<const HeightPriorModel>(factor);
}

}  // namespace hba::graph
