#pragma once
// The BA cost of a fixed set of plane features (one association) over K
// frames: evaluation of the cost and assembly of the full gradient and
// Hessian. Planes are processed in parallel; every sum is taken in a fixed
// order, so results are bit-identical for any thread count.
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "hba/ba/plane_cost.hpp"
#include "hba/ba/plane_spread.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

struct Linearization {
  double cost = 0.0;
  Eigen::VectorXd gradient;  // 6K, convention of window_ba.hpp
  Eigen::MatrixXd hessian;   // 6K x 6K, not gauge-fixed
};

class PlaneProblem {
 public:
  // Throws hba::Error if a plane names a frame >= num_frames, or lists its
  // clusters other than in strictly ascending frame order.
  PlaneProblem(std::vector<PlaneObservation> planes, std::size_t num_frames);

  // `planes`: chunks [spread.first_chunk, spread.end_chunk) of a problem
  // spread over spread.group (plane_spread.hpp).
  PlaneProblem(std::vector<PlaneObservation> planes, std::size_t num_frames, PlaneSpread spread);

  std::size_t numFrames() const { return num_frames_; }
  // The planes this process holds: all of them unless spread.
  std::size_t numPlanes() const { return planes_.size(); }
  const std::vector<PlaneObservation>& planes() const { return planes_; }
  const PlaneSpread& spread() const { return spread_; }

  // Per-plane costs (N * lambda_min) of the planes held, in plane order.
  std::vector<double> planeCosts(const std::vector<Pose>& poses) const;
  // Of every plane, gathered from the group when spread (a collective).
  std::vector<double> allPlaneCosts(const std::vector<Pose>& poses) const;
  double cost(const std::vector<Pose>& poses) const;  // of every plane
  // The sum of per-plane costs as cost() takes it (in order: deterministic).
  static double total(const std::vector<double>& plane_costs);
  Linearization linearize(const std::vector<Pose>& poses) const;

 private:
  std::vector<PlaneObservation> planes_;
  std::size_t num_frames_ = 0;
  PlaneSpread spread_;
};

}  // namespace hba::ba
