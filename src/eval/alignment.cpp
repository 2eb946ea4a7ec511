#include "hba/eval/alignment.hpp"

#include <Eigen/SVD>

#include "hba/core/error.hpp"

namespace hba::eval {

Pose Similarity::apply(const Pose& pose) const { return Pose(Mat3(R * pose.R()), apply(pose.t)); }

Similarity umeyama(const std::vector<Vec3>& source, const std::vector<Vec3>& target, bool with_scale) {
  if (source.size() != target.size()) throw Error("alignment: point lists differ in length");
  const std::size_t n = source.size();
  if (n < 3) throw Error("alignment needs at least 3 matched poses, got " + std::to_string(n));

  Vec3 mean_source = Vec3::Zero(), mean_target = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_source += source[i];
    mean_target += target[i];
  }
  mean_source /= static_cast<double>(n);
  mean_target /= static_cast<double>(n);

  Mat3 cross = Mat3::Zero();  // (1/n) sum (y - mu_y)(x - mu_x)^T
  double source_variance = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 x = source[i] - mean_source;
    cross += (target[i] - mean_target) * x.transpose();
    source_variance += x.squaredNorm();
  }
  cross /= static_cast<double>(n);
  source_variance /= static_cast<double>(n);
  if (source_variance <= 1e-18) throw Error("alignment: all estimated positions coincide");

  const Eigen::JacobiSVD<Mat3> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Flip the weakest axis when U V^T would be a reflection.
  Vec3 signs = Vec3::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) signs.z() = -1.0;

  Similarity s;
  s.R = svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
  s.scale = with_scale ? svd.singularValues().dot(signs) / source_variance : 1.0;
  s.t = mean_target - s.scale * (s.R * mean_source);
  return s;
}

Similarity alignTrajectory(const std::vector<Pose>& reference, const std::vector<Pose>& estimate,
                           Alignment alignment) {
  if (alignment == Alignment::None) return Similarity{};
  std::vector<Vec3> source, target;
  source.reserve(estimate.size());
  target.reserve(reference.size());
  for (const Pose& p : estimate) source.push_back(p.t);
  for (const Pose& p : reference) target.push_back(p.t);
  return umeyama(source, target, alignment == Alignment::Sim3);
}

}  // namespace hba::eval
