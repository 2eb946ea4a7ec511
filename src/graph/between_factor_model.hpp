#pragma once
// The part of FactorModel shared by the kinds that measure the relative pose
// of two nodes (relative and loop-closure factors): one residual, one cost.
#include <cstddef>
#include <string>
#include <vector>

#include "factor_model.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

class BetweenFactorModel : public FactorModel {
 public:
  BetweenFactorModel(std::size_t from, std::size_t to, const Pose& measurement, const Mat6& information);

  std::vector<std::size_t> nodes() const override { return {from_, to_}; }
  void validate(std::size_t num_poses, const std::string& label) const override;
  double cost(const std::vector<Pose>& poses) const override;
  ceres::CostFunction* newCost() const override;

 private:
  std::size_t from_;
  std::size_t to_;
  Pose measurement_;
  Mat6 information_;
};

}  // namespace hba::graph
