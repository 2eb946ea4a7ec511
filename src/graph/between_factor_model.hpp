#pragma once
// The model of a between factor (hba/graph/factors.hpp): the relative pose
// of two nodes, one residual whatever its loss tag. A window's factors are
// named "relative", loop closures "loop closure".
#include <cstddef>
#include <string>
#include <vector>

#include "factor_model.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

class BetweenFactorModel final : public FactorModel {
 public:
  BetweenFactorModel(std::size_t from, std::size_t to, const Pose& measurement, const Mat6& information,
                     BetweenLoss loss);

  const char* name() const override { return loss_ == BetweenLoss::Loop ? "loop closure" : "relative"; }
  LossGroup lossGroup() const override {
    return loss_ == BetweenLoss::Loop ? LossGroup::Loop : LossGroup::Window;
  }
  std::vector<std::size_t> nodes() const override { return {from_, to_}; }
  void validate(std::size_t num_poses, const std::string& label) const override;
  double cost(const std::vector<Pose>& poses) const override;
  ceres::CostFunction* newCost() const override;

 private:
  std::size_t from_;
  std::size_t to_;
  Pose measurement_;
  Mat6 information_;
  BetweenLoss loss_;
};

}  // namespace hba::graph
