#include "tangent_solver.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/cost_function.h>

#include "factor_model.hpp"
#include "hba/core/error.hpp"
#include "normal_equations.hpp"
#include "pose_block.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

// The graph's factors, each adding its own terms or through its Ceres cost.
class Linearization {
 public:
  explicit Linearization(const FactorGraph& factors) : models_(factors.models()) {
    for (const auto& model : models_) {
      nodes_.push_back(model->nodes());
      costs_.emplace_back(model->formsNormalEquations() ? nullptr : model->newCost());
    }
  }
  const std::vector<std::vector<std::size_t>>& nodes() const { return nodes_; }

  void at(const std::vector<Pose>& poses, NormalEquations& system) const {
    system.clear();
    for (std::size_t k = 0; k < models_.size(); ++k) {
      if (costs_[k]) {
        addTermsFromCost(*costs_[k], nodes_[k], poses, system);
      } else {
        models_[k]->addNormalEquations(poses, system);
      }
    }
  }

  double cost(const std::vector<Pose>& poses) const {
    double sum = 0.0;
    for (const auto& model : models_) sum += model->cost(poses);
    return sum;
  }

 private:
  const std::vector<std::shared_ptr<const FactorModel>>& models_;
  std::vector<std::vector<std::size_t>> nodes_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
};

std::vector<Pose> plus(const std::vector<Pose>& poses, const std::vector<Vec6>& delta) {
  const WorldPoseManifold manifold;
  std::vector<Pose> moved = poses;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (delta[k].isZero(0.0)) continue;
    const PoseBlock from = toPoseBlock(poses[k]);
    PoseBlock to{};
    manifold.Plus(from.data(), delta[k].data(), to.data());
    moved[k] = poseFromBlock(to.data());
  }
  return moved;
}

// Norms as Ceres' parameter tolerance takes them: the step in the tangent,
// the poses as their 7 numbers each.
double stepNorm(const std::vector<Vec6>& delta) {
  double sum = 0.0;
  for (const Vec6& d : delta) sum += d.squaredNorm();
  return std::sqrt(sum);
}

double posesNorm(const std::vector<Pose>& poses, const std::vector<bool>& variable) {
  double sum = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k)
    if (variable[k]) sum += poses[k].t.squaredNorm() + poses[k].q.coeffs().squaredNorm();
  return std::sqrt(sum);
}

}  // namespace

TangentSolve solveInTangent(const std::vector<Pose>& initial, const FactorGraph& factors,
                            const std::vector<bool>& variable, const PoseGraphSettings& settings) {
  constexpr double kParameterTolerance = 1e-8;  // Ceres' default
  const Linearization linearization(factors);
  NormalEquations system(variable, linearization.nodes());
  TangentSolve out;
  out.poses = initial;
  linearization.at(out.poses, system);
  out.initial_cost = out.final_cost = system.cost();
  // Ceres' Levenberg-Marquardt: the damping from an initial trust region
  // of 1e4, shrunk or grown by how well the model predicted the step.
  double lambda = 1e-4;
  double growth = 2.0;
  // After a step, the next one first reuses the last factorization with the
  // new gradient (a chord step: a solve instead of a factorization, which
  // is most of an iteration's time); it is taken while each such step gains
  // less than a tenth of the one before, i.e. while the Hessian has barely
  // changed. Near the minimum the pose graph is almost linear, so the steps
  // that follow the first are nearly all of this kind.
  constexpr double kChordContraction = 0.1;
  bool chord = false;
  double last_gain = 0.0;
  std::vector<Vec6> delta;
  while (out.iterations < settings.max_iterations) {
    if (out.final_cost <= 0.0) {
      out.converged = true;
      break;
    }
    ++out.iterations;
    if (!chord && !system.factorDamped(lambda)) {
      lambda *= growth;
      growth *= 2.0;
      continue;
    }
    if (!system.solve(delta)) throw Error("pose graph: CHOLMOD could not solve the normal equations");
    const double step = stepNorm(delta);
    if (step <= kParameterTolerance * (posesNorm(out.poses, variable) + kParameterTolerance)) {
      out.converged = true;
      break;
    }
    const std::vector<Pose> trial = plus(out.poses, delta);
    const double trial_cost = linearization.cost(trial);
    const double predicted = system.predictedDecrease(delta);
    const double gain = out.final_cost - trial_cost;
    const bool was_chord = chord;
    if (!(gain > 0.0) || !(predicted > 0.0) || (was_chord && gain > kChordContraction * last_gain)) {
      chord = false;  // factor afresh, at the same damping
      if (was_chord) continue;
      lambda *= growth;
      growth *= 2.0;
      if (lambda > 1e32) break;
      continue;
    }
    if (!was_chord) {
      const double ratio = gain / predicted;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * ratio - 1.0, 3));
      growth = 2.0;
    }
    const double share = gain / out.final_cost;
    out.poses = trial;
    out.final_cost = trial_cost;
    last_gain = gain;
    chord = true;
    // A chord step converges only linearly: what is left after it may be
    // as much as a tenth of its gain (kChordContraction), along the weak
    // directions too, so it ends the solve at a hundredth of the share.
    const double end_share = was_chord ? kChordContraction * kChordContraction : 1.0;
    if (share < end_share * settings.last_step_gain || share < end_share * settings.function_tolerance) {
      out.converged = true;
      break;
    }
    linearization.at(out.poses, system);
    out.final_cost = system.cost();
  }
  return out;
}

}  // namespace hba::graph
