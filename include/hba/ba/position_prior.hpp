#pragma once
// Absolute position priors inside a plane BA (GNSS, surveyed points): a
// point fixed in one frame (its origin, or a point of a rigid group of
// frames) should lie at a world position. In the refinement they hold the
// long-range shape where the priors define it, while the planes, with
// thousands of points a frame, keep deciding the local shape: a prior's
// sigma of decimetres is a weak pull next to them.
#include <cstddef>
#include <utility>
#include <vector>

#include "hba/ba/plane_problem.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::ba {

// e = R_frame * offset + t_frame - position; cost e^T W e in plane-cost
// units (m^2): W = point_sigma^2 * information, as the motion prior's.
struct PositionTerm {
  std::size_t frame = 0;
  Vec3 offset = Vec3::Zero();  // in the frame's coordinates
  Vec3 position = Vec3::Zero();
  Mat3 weight = Mat3::Zero();
};

class PositionPriors {
 public:
  PositionPriors() = default;
  explicit PositionPriors(std::vector<PositionTerm> terms) : terms_(std::move(terms)) {}

  const std::vector<PositionTerm>& terms() const { return terms_; }
  bool empty() const { return terms_.empty(); }
  double cost(const std::vector<Pose>& poses) const;
  // Derivative of a term's error by its frame's update (translation, then
  // rotation about the world axes: hba/ba/lm_solver.hpp's applyUpdate).
  static Eigen::Matrix<double, 3, 6> jacobian(const PositionTerm& term, const Pose& pose);
  static Vec3 error(const PositionTerm& term, const Pose& pose);

  // The rigid move of all frames (applied on the left: move * pose) that
  // minimizes the priors' cost. The plane cost and the motion prior do not
  // change under it: it is the part of a step that conjugate gradients,
  // working locally, reach last (a whole sequence turned by a degree
  // about its held-free first frame).
  Pose bestRigidMove(const std::vector<Pose>& poses) const;

  // True when the priors' positions spread at least `min_spread_m` (one
  // sigma) along two directions: then they fix the frame (translation and
  // rotation) and no pose needs to be held as the gauge.
  bool defineTheFrame(double min_spread_m) const;

 private:
  std::vector<PositionTerm> terms_;
};

}  // namespace hba::ba
