#include "hba/closure/feature_registration.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "core/kd_tree.hpp"
#include "hba/core/lie.hpp"

namespace hba::closure {
namespace {

using Matches = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Pose fitPose(const FeatureCloud& source, const FeatureCloud& target, const Matches& matches,
             const std::vector<std::size_t>& chosen) {
  Eigen::Matrix3Xd from(3, chosen.size()), to(3, chosen.size());
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    from.col(static_cast<Eigen::Index>(k)) = source.points[matches[chosen[k]].first].cast<double>();
    to.col(static_cast<Eigen::Index>(k)) = target.points[matches[chosen[k]].second].cast<double>();
  }
  return Pose::fromMatrix(Eigen::umeyama(from, to, false));
}

std::vector<std::size_t> agreeing(const FeatureCloud& source, const FeatureCloud& target,
                                  const Matches& matches, const Pose& pose, double reach) {
  std::vector<std::size_t> inliers;
  const double reach_sq = reach * reach;
  for (std::size_t k = 0; k < matches.size(); ++k) {
    const Vec3 moved = pose * source.points[matches[k].first].cast<double>();
    if ((moved - target.points[matches[k].second].cast<double>()).squaredNorm() < reach_sq)
      inliers.push_back(k);
  }
  return inliers;
}

// How many matches `pose` brings within `reach`; stops early once it can no
// longer beat `to_beat`.
std::size_t countAgreeing(const FeatureCloud& source, const FeatureCloud& target, const Matches& matches,
                          const Pose& pose, double reach, std::size_t to_beat) {
  const double reach_sq = reach * reach;
  std::size_t count = 0;
  for (std::size_t k = 0; k < matches.size(); ++k) {
    if (count + (matches.size() - k) <= to_beat) break;
    const Vec3 moved = pose * source.points[matches[k].first].cast<double>();
    if ((moved - target.points[matches[k].second].cast<double>()).squaredNorm() < reach_sq) ++count;
  }
  return count;
}

// Side lengths of a triple alike in both clouds (a rigid motion keeps them),
// and long enough to fix a rotation.
bool sidesAgree(const FeatureCloud& source, const FeatureCloud& target, const Matches& matches,
                const std::size_t (&triple)[3], double similarity, double min_side) {
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    const double s =
        (source.points[matches[triple[a]].first] - source.points[matches[triple[b]].first]).norm();
    const double t =
        (target.points[matches[triple[a]].second] - target.points[matches[triple[b]].second]).norm();
    if (std::min(s, t) < similarity * std::max(s, t) || std::min(s, t) < min_side) return false;
  }
  return true;
}

// Point-to-plane ICP from `start`; updates `result` with the pose and fitness.
void refineByIcp(const FeatureCloud& source, const FeatureCloud& target, const Pose& start,
                 const RegistrationSettings& settings, Registration& result) {
  const KdTree<3> tree(target.points);
  const double reach = settings.icp_reach_voxels * target.voxel;
  const double inlier = settings.inlier_voxels * target.voxel;
  Pose pose = start;
  for (std::size_t iteration = 0; iteration <= settings.icp_iterations; ++iteration) {
    Mat6 normal_matrix = Mat6::Zero();
    Vec6 gradient = Vec6::Zero();
    std::size_t on_surface = 0;
    double squared = 0.0;
    for (const Vec3f& s : source.points) {
      const Vec3 p = pose * s.cast<double>();
      const auto [j, d_sq] = tree.nearest(p.cast<float>());
      if (j >= target.points.size() || d_sq > reach * reach) continue;
      const Vec3 n = target.normals[j].cast<double>();
      const double r = n.dot(p - target.points[j].cast<double>());
      if (d_sq < inlier * inlier) {
        ++on_surface;
        squared += r * r;
      }
      Vec6 jacobian;
      jacobian << n, p.cross(n);
      normal_matrix += jacobian * jacobian.transpose();
      gradient += jacobian * r;
    }
    result.fitness = source.points.empty() ? 0.0 : static_cast<double>(on_surface) / source.points.size();
    result.rms_m = on_surface > 0 ? std::sqrt(squared / static_cast<double>(on_surface)) : 0.0;
    if (iteration == settings.icp_iterations) break;
    const Vec6 step = normal_matrix.ldlt().solve(-gradient);
    if (!step.allFinite()) break;
    const Pose update(so3Exp(step.tail<3>()), step.head<3>());
    pose = update * pose;
    if (step.norm() < 1e-6) break;
  }
  result.target_from_source = pose;
}

}  // namespace

Matches mutualMatches(const FeatureCloud& source, const FeatureCloud& target) {
  Matches matches;
  const auto ns = static_cast<Eigen::Index>(source.features.size());
  const auto nt = static_cast<Eigen::Index>(target.features.size());
  if (ns == 0 || nt == 0) return matches;
  // Every squared distance at once, |s|^2 + |t|^2 - 2 s.t, by one matrix
  // product: in 33 dimensions a k-d tree visits most of itself anyway.
  const Eigen::Map<const Eigen::MatrixXf> s(source.features.front().data(), 33, ns);
  const Eigen::Map<const Eigen::MatrixXf> t(target.features.front().data(), 33, nt);
  Eigen::MatrixXf distance = -2.0F * (s.transpose() * t);
  distance.colwise() += s.colwise().squaredNorm().transpose();
  distance.rowwise() += t.colwise().squaredNorm();
  // Each target's nearest source down its column; each source's nearest
  // target by a running minimum over the columns (both read memory in order).
  Eigen::VectorXf best_distance = distance.col(0);
  std::vector<Eigen::Index> nearest_target(static_cast<std::size_t>(ns), 0);
  for (Eigen::Index j = 1; j < nt; ++j) {
    for (Eigen::Index i = 0; i < ns; ++i) {
      if (distance(i, j) < best_distance(i)) {
        best_distance(i) = distance(i, j);
        nearest_target[static_cast<std::size_t>(i)] = j;
      }
    }
  }
  for (Eigen::Index j = 0; j < nt; ++j) {
    Eigen::Index i = 0;
    distance.col(j).minCoeff(&i);
    if (nearest_target[static_cast<std::size_t>(i)] == j) {
      matches.emplace_back(source.keypoints[static_cast<std::size_t>(i)],
                           target.keypoints[static_cast<std::size_t>(j)]);
    }
  }
  return matches;
}

Registration registerClouds(const FeatureCloud& source, const FeatureCloud& target,
                            const RegistrationSettings& settings) {
  Registration result;
  const Matches matches = mutualMatches(source, target);
  result.matches = matches.size();
  if (matches.size() < 3) {
    result.reason = std::to_string(matches.size()) + " descriptor matches";
    return result;
  }
  const double reach = settings.inlier_voxels * target.voxel;
  std::mt19937 random(settings.seed);
  std::vector<std::size_t> best;
  Pose best_pose;
  std::size_t hypotheses = 0, needed = settings.max_hypotheses;
  for (std::size_t draw = 0; draw < settings.max_draws && hypotheses < needed; ++draw) {
    std::size_t triple[3];
    for (std::size_t& index : triple) index = random() % matches.size();
    if (triple[0] == triple[1] || triple[1] == triple[2] || triple[0] == triple[2]) continue;
    if (!sidesAgree(source, target, matches, triple, settings.edge_similarity, 2.0 * target.voxel)) continue;
    ++hypotheses;
    const Pose pose = fitPose(source, target, matches, {triple[0], triple[1], triple[2]});
    if (countAgreeing(source, target, matches, pose, reach, best.size()) <= best.size()) continue;
    best = agreeing(source, target, matches, pose, reach);
    best_pose = pose;
    // Enough draws to have drawn three inliers with 99.9 % odds, had the
    // best pose's share of inliers been the true one.
    const double share = static_cast<double>(best.size()) / static_cast<double>(matches.size());
    const double miss = 1.0 - share * share * share;
    if (miss < 1.0) {
      needed =
          std::min(settings.max_hypotheses,
                   static_cast<std::size_t>(std::ceil(std::log(1e-3) / std::log(std::max(miss, 1e-12)))));
    }
  }
  // The estimate from all its inliers, twice (the set may grow).
  for (int round = 0; round < 2 && best.size() >= 3; ++round) {
    best_pose = fitPose(source, target, matches, best);
    best = agreeing(source, target, matches, best_pose, reach);
  }
  result.inliers = best.size();
  if (best.size() < std::max<std::size_t>(3, settings.min_inliers)) {
    result.reason = std::to_string(best.size()) + " of " + std::to_string(matches.size()) +
                    " descriptor matches agree on a pose (" + std::to_string(settings.min_inliers) +
                    " needed)";
    return result;
  }
  refineByIcp(source, target, best_pose, settings, result);
  result.found = true;
  return result;
}

}  // namespace hba::closure
