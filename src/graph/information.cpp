#include "hba/graph/information.hpp"

#include <cmath>
#include <string>

#include "anchored_covariance.hpp"
#include "clamped_inverse.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"

namespace hba::graph {
namespace {

Eigen::MatrixXd withoutFrame(const Eigen::MatrixXd& m, std::size_t frame) {
  const Eigen::Index n = m.rows();
  const Eigen::Index start = static_cast<Eigen::Index>(6 * frame);
  const Eigen::Index after = n - start - 6;
  Eigen::MatrixXd out(n - 6, n - 6);
  out.topLeftCorner(start, start) = m.topLeftCorner(start, start);
  out.topRightCorner(start, after) = m.topRightCorner(start, after);
  out.bottomLeftCorner(after, start) = m.bottomLeftCorner(after, start);
  out.bottomRightCorner(after, after) = m.bottomRightCorner(after, after);
  return out;
}

}  // namespace

void validateWindowHessian(const Eigen::MatrixXd& hessian, const std::vector<Pose>& poses,
                           const InformationSettings& settings) {
  const auto expected = static_cast<Eigen::Index>(6 * poses.size());
  if (poses.size() < 2) throw Error("graph information: a window needs at least two poses");
  if (hessian.rows() != expected || hessian.cols() != expected) {
    throw Error("graph information: Hessian is " + std::to_string(hessian.rows()) + "x" +
                std::to_string(hessian.cols()) + ", expected " + std::to_string(expected) + "x" +
                std::to_string(expected) + " for " + std::to_string(poses.size()) + " poses");
  }
  if (!hessian.allFinite()) throw Error("graph information: Hessian has non-finite entries");
  if (!(settings.point_sigma > 0.0) || !std::isfinite(settings.point_sigma)) {
    throw Error("graph information: point_sigma must be positive");
  }
  if (!(settings.min_eigen_ratio > 0.0 && settings.min_eigen_ratio <= 1.0)) {
    throw Error("graph information: min_eigen_ratio must be in (0, 1]");
  }
  if (!(settings.fallback_information > 0.0) || !std::isfinite(settings.fallback_information)) {
    throw Error("graph information: fallback_information must be positive");
  }
}

namespace {

// The Fisher information of the frames but `anchor`, the anchor held fixed.
Eigen::MatrixXd anchoredFisher(const Eigen::MatrixXd& hessian, std::size_t anchor,
                               const InformationSettings& settings) {
  // cost / (2 sigma^2) is the negative log-likelihood of Gaussian distances.
  const double to_fisher = 1.0 / (2.0 * settings.point_sigma * settings.point_sigma);
  // Holding the anchor fixed removes the 6-dim gauge freedom: the relative
  // pose is invariant to a rigid motion of the whole window, so any such
  // choice yields the same covariance for it.
  return withoutFrame(hessian, anchor) * to_fisher;
}

}  // namespace

std::optional<Eigen::MatrixXd> anchoredCovariance(const Eigen::MatrixXd& hessian, std::size_t anchor,
                                                  const InformationSettings& settings) {
  return clampedInverse(anchoredFisher(hessian, anchor, settings), settings.min_eigen_ratio);
}

std::optional<Eigen::MatrixXd> anchoredInformation(const Eigen::MatrixXd& hessian, std::size_t anchor,
                                                   const InformationSettings& settings) {
  return clampedUp(anchoredFisher(hessian, anchor, settings), settings.min_eigen_ratio);
}

Mat6 relativeInformationFromAnchored(const std::optional<Eigen::MatrixXd>& covariance,
                                     const std::vector<Pose>& poses, std::size_t anchor, std::size_t a,
                                     std::size_t b, const InformationSettings& settings) {
  const Mat6 fallback = settings.fallback_information * Mat6::Identity();
  if (!covariance) return fallback;

  // Linearized at the measurement itself (E = I): e ~ J_a d_a + J_b d_b, where
  // the anchor's perturbation is zero.
  const Pose measurement = relative(poses[a], poses[b]);
  const RelativePoseErrorJacobians J = relativePoseErrorJacobians(measurement, poses[a], poses[b]);
  const std::size_t frames[2] = {a, b};
  const Mat6* jacobians[2] = {&J.d_from, &J.d_to};
  // Row of a frame's block in the covariance, which lacks the anchor's block.
  auto blockStart = [anchor](std::size_t frame) {
    return static_cast<Eigen::Index>(6 * (frame < anchor ? frame : frame - 1));
  };
  Mat6 cov_error = Mat6::Zero();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (frames[i] == anchor || frames[j] == anchor) continue;
      cov_error += *jacobians[i] * covariance->block<6, 6>(blockStart(frames[i]), blockStart(frames[j])) *
                   jacobians[j]->transpose();
    }
  }
  const auto information = clampedInverse(cov_error, settings.min_eigen_ratio);
  if (!information) return fallback;
  return *information;
}

Mat6 relativePoseInformation(const Eigen::MatrixXd& hessian, const std::vector<Pose>& poses, std::size_t a,
                             std::size_t b, const InformationSettings& settings) {
  validateWindowHessian(hessian, poses, settings);
  if (a == b) throw Error("graph information: a relative pose needs two distinct frames");
  if (a >= poses.size() || b >= poses.size()) {
    throw Error("graph information: frame index out of range (window of " + std::to_string(poses.size()) +
                " poses)");
  }
  return relativeInformationFromAnchored(anchoredCovariance(hessian, kGaugeFrame, settings), poses,
                                         kGaugeFrame, a, b, settings);
}

}  // namespace hba::graph
