#pragma once
// Ceres cost of one relative-pose factor: the whitened residual
// S * e(T_from, T_to) with S^T S = information, over two PoseBlocks.
#include <ceres/sized_cost_function.h>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::graph {

// S with S^T S = information, from the eigen-decomposition of its symmetric
// part, so that a positive semi-definite (singular) information works too.
// Throws hba::Error on non-finite entries or a clearly negative eigenvalue.
Mat6 squareRootInformation(const Mat6& information);

class RelativePoseCost final : public ceres::SizedCostFunction<6, 7, 7> {
 public:
  RelativePoseCost(const Pose& measurement, const Mat6& sqrt_information);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Pose measurement_;
  Mat6 sqrt_information_;
};

}  // namespace hba::graph
