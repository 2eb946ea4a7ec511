#include "between_factor_model.hpp"

#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "information_root.hpp"
#include "relative_pose_cost.hpp"

namespace hba::graph {

BetweenFactorModel::BetweenFactorModel(std::size_t from, std::size_t to, const Pose& measurement,
                                       const Mat6& information, BetweenLoss loss)
    : from_(from), to_(to), measurement_(measurement), information_(information), loss_(loss) {}

FactorModelPtr betweenModel(std::size_t from, std::size_t to, const Pose& measurement,
                            const Mat6& information, BetweenLoss loss) {
  return std::make_shared<const BetweenFactorModel>(from, to, measurement, information, loss);
}

void BetweenFactorModel::validate(std::size_t num_poses, const std::string& label) const {
  checkNode(from_, num_poses, label);
  checkNode(to_, num_poses, label);
  if (from_ == to_) throw Error(label + " links node " + std::to_string(from_) + " to itself");
  checkFinite(measurement_, label);
  informationRoot<6>(information_, label + ": information");
}

double BetweenFactorModel::cost(const std::vector<Pose>& poses) const {
  const Vec6 e = relativePoseError(measurement_, poses[from_], poses[to_]);
  return e.dot(information_ * e);
}

ceres::CostFunction* BetweenFactorModel::newCost() const {
  return new RelativePoseCost(measurement_, squareRootInformation(information_));
}

}  // namespace hba::graph
