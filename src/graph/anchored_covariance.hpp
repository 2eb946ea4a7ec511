#pragma once
// The two steps of relativePoseInformation, split so that all factors of a
// window share one (costly) inversion.
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "hba/core/pose.hpp"
#include "hba/graph/information.hpp"

namespace hba::graph {

// Throws hba::Error unless `hessian` is a finite 6K x 6K matrix for K = poses.size() >= 2
// and the settings are valid.
void validateWindowHessian(const Eigen::MatrixXd& hessian, const std::vector<Pose>& poses,
                           const InformationSettings& settings);

// Covariance of all frames but `anchor` (in frame order) given that frame
// `anchor` is held fixed; nullopt when the Hessian carries no information.
std::optional<Eigen::MatrixXd> anchoredCovariance(const Eigen::MatrixXd& hessian, std::size_t anchor,
                                                  const InformationSettings& settings);

// The same frames' information, weak directions raised as for that
// covariance (its inverse); nullopt where it is.
std::optional<Eigen::MatrixXd> anchoredInformation(const Eigen::MatrixXd& hessian, std::size_t anchor,
                                                   const InformationSettings& settings);

// The frame that holds the gauge: the window's first, as in the BA itself.
inline constexpr std::size_t kGaugeFrame = 0;

// Information of the relative pose a -> b from that covariance.
Mat6 relativeInformationFromAnchored(const std::optional<Eigen::MatrixXd>& covariance,
                                     const std::vector<Pose>& poses, std::size_t anchor, std::size_t a,
                                     std::size_t b, const InformationSettings& settings);

}  // namespace hba::graph
