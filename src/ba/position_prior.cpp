#include "hba/ba/position_prior.hpp"

#include <algorithm>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "hba/core/lie.hpp"

namespace hba::ba {

Vec3 PositionPriors::error(const PositionTerm& term, const Pose& pose) {
  return pose.R() * term.offset + pose.t - term.position;
}

Eigen::Matrix<double, 3, 6> PositionPriors::jacobian(const PositionTerm& term, const Pose& pose) {
  // t + dt and exp(dphi) R: d(R o) / d dphi = -[R o]x.
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>() = Mat3::Identity();
  J.rightCols<3>() = -hat(pose.R() * term.offset);
  return J;
}

double PositionPriors::cost(const std::vector<Pose>& poses) const {
  double total = 0.0;
  for (const PositionTerm& term : terms_) {
    const Vec3 e = error(term, poses[term.frame]);
    total += e.dot(term.weight * e);
  }
  return total;
}

Pose PositionPriors::bestRigidMove(const std::vector<Pose>& poses) const {
  if (terms_.empty()) return Pose();
  // Gauss-Newton on (translation, rotation about the terms' centre): the
  // cost is quadratic in the translation and nearly so in small turns.
  Pose move;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Vec3 centre = Vec3::Zero();
    for (const PositionTerm& term : terms_) centre += (move * poses[term.frame]) * term.offset;
    centre /= static_cast<double>(terms_.size());
    Mat6 H = Mat6::Zero();
    Vec6 g = Vec6::Zero();
    for (const PositionTerm& term : terms_) {
      const Vec3 x = (move * poses[term.frame]) * term.offset;
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = Mat3::Identity();
      J.rightCols<3>() = -hat(x - centre);
      const Vec3 e = x - term.position;
      H += J.transpose() * term.weight * J;
      g += J.transpose() * term.weight * e;
    }
    // A light damping keeps turns about a line of priors (free) at zero.
    H.diagonal() += Vec6::Constant(1e-9 * std::max(H.trace(), 1e-300));
    const Vec6 step = -H.ldlt().solve(g);
    if (!step.allFinite()) break;
    const Mat3 turn = so3Exp(step.tail<3>());
    // x -> turn (x - c) + c + dt
    const Pose increment(turn, Vec3(centre - turn * centre + step.head<3>()));
    move = increment * move;
    if (step.head<3>().norm() < 1e-9 && step.tail<3>().norm() < 1e-12) break;
  }
  return move;
}

bool PositionPriors::defineTheFrame(double min_spread_m) const {
  if (terms_.size() < 3) return false;
  Vec3 mean = Vec3::Zero();
  for (const PositionTerm& term : terms_) mean += term.position;
  mean /= static_cast<double>(terms_.size());
  Mat3 scatter = Mat3::Zero();
  for (const PositionTerm& term : terms_) {
    const Vec3 d = term.position - mean;
    scatter += d * d.transpose();
  }
  scatter /= static_cast<double>(terms_.size());
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter);
  // Ascending: the middle one is the second-largest spread.
  return eig.eigenvalues()(1) >= min_spread_m * min_spread_m;
}

}  // namespace hba::ba
