#include "hba/ba/motion_prior.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"

namespace hba::ba {
namespace {

void validate(const MotionPriorSettings& s) {
  const bool ok = s.translation_sigma > 0.0 && s.translation_per_m >= 0.0 && s.rotation_sigma_deg > 0.0 &&
                  s.rotation_per_m_deg >= 0.0 && s.point_sigma > 0.0 &&
                  std::isfinite(s.translation_sigma + s.translation_per_m + s.rotation_sigma_deg +
                                s.rotation_per_m_deg + s.point_sigma);
  if (!ok) {
    throw Error("motion prior: sigmas must be positive and finite, growth rates >= 0");
  }
}

}  // namespace

double MotionPrior::cost(const std::vector<Pose>& poses) const {
  double total = 0.0;
  for (const RelativePosePrior& term : terms_) {
    const Vec6 e = relativePoseError(term.measurement, poses[term.from], poses[term.to]);
    total += e.dot(term.weight * e);
  }
  return total;
}

void MotionPrior::addTo(Linearization& lin, const std::vector<Pose>& poses) const {
  for (const RelativePosePrior& term : terms_) {
    const RelativePoseErrorJacobians J =
        relativePoseErrorJacobians(term.measurement, poses[term.from], poses[term.to]);
    const Eigen::Index a = static_cast<Eigen::Index>(6 * term.from);
    const Eigen::Index b = static_cast<Eigen::Index>(6 * term.to);
    const Mat6 WJa = term.weight * J.d_from;
    const Mat6 WJb = term.weight * J.d_to;
    lin.cost += J.error.dot(term.weight * J.error);
    lin.gradient.segment<6>(a) += 2.0 * J.d_from.transpose() * term.weight * J.error;
    lin.gradient.segment<6>(b) += 2.0 * J.d_to.transpose() * term.weight * J.error;
    lin.hessian.block<6, 6>(a, a) += 2.0 * J.d_from.transpose() * WJa;
    lin.hessian.block<6, 6>(a, b) += 2.0 * J.d_from.transpose() * WJb;
    lin.hessian.block<6, 6>(b, a) += 2.0 * J.d_to.transpose() * WJa;
    lin.hessian.block<6, 6>(b, b) += 2.0 * J.d_to.transpose() * WJb;
  }
}

MotionPrior neighbourPrior(const std::vector<Pose>& initial, const std::vector<double>& path_m,
                           const MotionPriorSettings& settings) {
  validate(settings);
  if (!settings.enabled || initial.size() < 2) return {};
  if (!path_m.empty() && path_m.size() + 1 != initial.size()) {
    throw Error("motion prior: " + std::to_string(path_m.size()) + " path lengths for " +
                std::to_string(initial.size()) + " frames");
  }
  const double point_variance = settings.point_sigma * settings.point_sigma;
  std::vector<RelativePosePrior> terms;
  terms.reserve(initial.size() - 1);
  for (std::size_t k = 0; k + 1 < initial.size(); ++k) {
    RelativePosePrior term;
    term.from = k;
    term.to = k + 1;
    term.measurement = relative(initial[k], initial[k + 1]);
    const double d = path_m.empty() ? term.measurement.t.norm() : path_m[k];
    const double sigma_t = settings.translation_sigma + settings.translation_per_m * d;
    const double sigma_r = (settings.rotation_sigma_deg + settings.rotation_per_m_deg * d) * M_PI / 180.0;
    term.weight.diagonal() << Vec3::Constant(point_variance / (sigma_t * sigma_t)),
        Vec3::Constant(point_variance / (sigma_r * sigma_r));
    terms.push_back(term);
  }
  return MotionPrior(std::move(terms));
}

std::vector<std::size_t> stepsBeyondThePrior(const std::vector<Pose>& initial,
                                             const std::vector<Pose>& result,
                                             const std::vector<double>& path_m,
                                             const MotionPriorSettings& settings, double sigmas) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k + 1 < initial.size() && k + 1 < result.size(); ++k) {
    const Pose before = initial[k].inverse() * initial[k + 1];
    const Pose change = before.inverse() * (result[k].inverse() * result[k + 1]);
    const double d = path_m.size() > k ? path_m[k] : before.t.norm();
    const double sigma_t = settings.translation_sigma + settings.translation_per_m * d;
    const double sigma_deg = settings.rotation_sigma_deg + settings.rotation_per_m_deg * d;
    const double angle_deg = Eigen::AngleAxisd(change.q).angle() * 180.0 / M_PI;
    if (change.t.norm() > sigmas * sigma_t || angle_deg > sigmas * sigma_deg) out.push_back(k);
  }
  return out;
}

void MotionPrior::tighten(const std::vector<std::size_t>& pairs, double factor) {
  for (RelativePosePrior& term : terms_) {
    if (std::binary_search(pairs.begin(), pairs.end(), term.from) && term.to == term.from + 1) {
      term.weight *= factor;
    }
  }
}

}  // namespace hba::ba
