#pragma once
// A weak prior that ties each frame of a BA window to its neighbour's
// relative pose as the input (odometry, or the chained keyframe poses of a
// lower layer) gave it. Where planes constrain a direction, thousands of
// point residuals outweigh it by orders of magnitude; where they do not (a
// pair of sparse scans that share only the ground, a corridor), it keeps the
// frames where odometry put them instead of letting LM slide them by metres
// along a direction that costs nothing. See docs/ba.md.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "hba/ba/plane_problem.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::ba {

// How far the input's relative pose between two neighbouring frames may be
// wrong (one sigma): a floor plus a share of the path between them, so that
// keyframes far apart (upper layers, the top layer's loops) may move far.
struct MotionPriorSettings {
  bool enabled = true;
  double translation_sigma = 0.1;   // m, floor
  double translation_per_m = 0.1;   // m per m of path between the frames
  double rotation_sigma_deg = 1.0;  // floor
  double rotation_per_m_deg = 0.2;  // deg per m of path
  // The plane cost is a sum of squared distances with this noise (m): the
  // prior is scaled into the same units (cost * 1/(2 sigma^2) is the
  // negative log-likelihood of both).
  double point_sigma = 0.02;
};

// e = relative-pose error of hba/core/relative_pose_error.hpp; cost e^T W e
// in plane-cost units (m^2).
struct RelativePosePrior {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose measurement;
  Mat6 weight = Mat6::Zero();
};

class MotionPrior {
 public:
  MotionPrior() = default;
  explicit MotionPrior(std::vector<RelativePosePrior> terms) : terms_(std::move(terms)) {}

  const std::vector<RelativePosePrior>& terms() const { return terms_; }
  // Multiplies the weight of the terms between frames k and k+1, for each k
  // in `pairs` (ascending), by `factor`.
  void tighten(const std::vector<std::size_t>& pairs, double factor);
  bool empty() const { return terms_.empty(); }
  double cost(const std::vector<Pose>& poses) const;
  // Adds the prior's cost, gradient and Gauss-Newton Hessian (2 J^T W J)
  // to a plane linearization over the same frames.
  void addTo(Linearization& lin, const std::vector<Pose>& poses) const;

 private:
  std::vector<RelativePosePrior> terms_;
};

// Priors between neighbouring frames k, k+1 at their relative pose in
// `initial`; `path_m[k]` is the path length (m) between frames k and k+1
// (empty: the straight distance). Throws hba::Error on invalid settings.
MotionPrior neighbourPrior(const std::vector<Pose>& initial, const std::vector<double>& path_m,
                           const MotionPriorSettings& settings);

// Indices k of the neighbouring pairs (k, k+1) of `result` that moved away
// from their relative pose in `initial` by more than `sigmas` standard
// deviations of the prior (translation or rotation): steps no odometry
// makes, the sign of a BA that slid frames along a direction its planes do
// not constrain (or that planes merging unrelated surfaces pulled).
std::vector<std::size_t> stepsBeyondThePrior(const std::vector<Pose>& initial,
                                             const std::vector<Pose>& result,
                                             const std::vector<double>& path_m,
                                             const MotionPriorSettings& settings, double sigmas);

}  // namespace hba::ba
