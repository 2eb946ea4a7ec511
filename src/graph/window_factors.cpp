#include "hba/graph/window_factors.hpp"

#include <algorithm>
#include <string>

#include <Eigen/LU>

#include "anchored_covariance.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"

namespace hba::graph {
namespace {

// The window frames that window frame `from` is linked to.
std::vector<std::size_t> partnersOf(std::size_t from, std::size_t count, FactorPairs pairs) {
  std::vector<std::size_t> partners;
  switch (pairs) {
    case FactorPairs::Adjacent:
      if (from + 1 < count) partners.push_back(from + 1);
      break;
    case FactorPairs::AllPairs:
      for (std::size_t to = from + 1; to < count; ++to) partners.push_back(to);
      break;
    case FactorPairs::FromFirst:
      if (from == 0) {
        for (std::size_t to = 1; to < count; ++to) partners.push_back(to);
      }
      break;
    case FactorPairs::Joint:
      break;  // one WindowShapeFactor instead
  }
  return partners;
}

void checkNodes(const std::vector<std::size_t>& nodes, std::size_t count) {
  if (nodes.size() != count) {
    throw Error("window factors: " + std::to_string(nodes.size()) + " nodes for a window of " +
                std::to_string(count) + " poses");
  }
  std::vector<std::size_t> sorted = nodes;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
    throw Error("window factors: two window frames map to the same layer-1 node");
  }
}

}  // namespace

std::vector<RelativePoseFactor> windowFactors(const Eigen::MatrixXd& hessian,
                                              const std::vector<Pose>& optimized_window_poses,
                                              const std::vector<std::size_t>& nodes, FactorPairs pairs,
                                              const InformationSettings& settings) {
  const std::vector<Pose>& poses = optimized_window_poses;
  validateWindowHessian(hessian, poses, settings);
  checkNodes(nodes, poses.size());

  const auto covariance = anchoredCovariance(hessian, kGaugeFrame, settings);
  std::vector<RelativePoseFactor> factors;
  for (std::size_t from = 0; from < poses.size(); ++from) {
    for (const std::size_t to : partnersOf(from, poses.size(), pairs)) {
      RelativePoseFactor factor;
      factor.from = nodes[from];
      factor.to = nodes[to];
      factor.measurement = relative(poses[from], poses[to]);
      factor.information =
          relativeInformationFromAnchored(covariance, poses, kGaugeFrame, from, to, settings);
      factors.push_back(factor);
    }
  }
  return factors;
}

WindowShapeFactor windowShapeFactor(const Eigen::MatrixXd& hessian,
                                    const std::vector<Pose>& optimized_window_poses,
                                    const std::vector<std::size_t>& nodes,
                                    const InformationSettings& settings) {
  const std::vector<Pose>& poses = optimized_window_poses;
  validateWindowHessian(hessian, poses, settings);
  checkNodes(nodes, poses.size());
  static_assert(kGaugeFrame == 0, "the shape is measured from the window's gauge frame");

  WindowShapeFactor factor;
  factor.nodes = nodes;
  const std::size_t frames = poses.size() - 1;
  const auto size = static_cast<Eigen::Index>(6 * frames);
  for (std::size_t k = 1; k < poses.size(); ++k) factor.relative.push_back(relative(poses[0], poses[k]));
  // No information at all: a factor that barely holds the frames.
  const Eigen::MatrixXd fallback = settings.fallback_information * Eigen::MatrixXd::Identity(size, size);
  const auto information = anchoredInformation(hessian, kGaugeFrame, settings);
  if (!information) {
    factor.information = fallback;
    return factor;
  }
  // Linearized at the measurement (E = I): e_k ~ J_k d_k with frame 0 held,
  // so the errors' covariance is J C J^T and their information
  // J^-T C^-1 J^-1, block by block. J_k is a rotation in each of its 3x3
  // blocks (R_k^T): the errors' covariance has the same eigenvalues as C,
  // so raising C's weak ones (clampedUp) leaves none to raise in it, and
  // no second eigen-decomposition of hundreds of rows is needed.
  std::vector<Mat6> inverse_jacobians;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    inverse_jacobians.push_back(
        relativePoseErrorJacobians(factor.relative[k - 1], poses[0], poses[k]).d_to.inverse());
  }
  factor.information.resize(size, size);
  for (std::size_t i = 0; i < frames; ++i) {
    for (std::size_t j = 0; j < frames; ++j) {
      const auto row = static_cast<Eigen::Index>(6 * i);
      const auto col = static_cast<Eigen::Index>(6 * j);
      factor.information.block<6, 6>(row, col) =
          inverse_jacobians[i].transpose() * information->block<6, 6>(row, col) * inverse_jacobians[j];
    }
  }
  if (!factor.information.allFinite()) factor.information = fallback;
  return factor;
}

}  // namespace hba::graph
