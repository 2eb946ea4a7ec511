#include "hba/ba/lm_solver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "hba/core/lie.hpp"

namespace hba::ba {
namespace {

constexpr double kMaxDamping = 1e12;

// Marquardt scaling: damp each unknown by its own curvature, with a floor so
// that an unknown no plane constrains (zero row) still gets a finite step of 0.
Eigen::VectorXd dampingScale(const Eigen::MatrixXd& H) {
  Eigen::VectorXd d = H.diagonal().cwiseMax(0.0);
  const double floor = std::max(1e-9 * d.maxCoeff(), 1e-12);
  return d.cwiseMax(floor);
}

bool isFinite(const Eigen::VectorXd& v) { return v.allFinite(); }

}  // namespace

std::vector<Pose> applyUpdate(const std::vector<Pose>& poses, const Eigen::VectorXd& delta) {
  std::vector<Pose> out = poses;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    // A frame with no update (the gauge frame) keeps its exact bits.
    if (delta.segment<6>(6 * i).isZero(0.0)) continue;
    const Vec3 dt = delta.segment<3>(6 * i);
    const Vec3 dphi = delta.segment<3>(6 * i + 3);
    out[i] = Pose(Mat3(so3Exp(dphi) * poses[i].R()), Vec3(poses[i].t + dt));
  }
  return out;
}

LmSummary solveLevenbergMarquardt(const PlaneProblem& problem, std::vector<Pose>& poses,
                                  const LmSettings& settings, const MotionPrior& prior,
                                  std::optional<double> start_plane_cost, Linearization* settled) {
  auto objective = [&](const std::vector<Pose>& at) { return problem.cost(at) + prior.cost(at); };
  LmSummary summary;
  // Costs are compared through cost() only, so rounding differences between
  // the two eigen solvers can never make an accepted step look uphill.
  double cost = start_plane_cost ? *start_plane_cost + prior.cost(poses) : objective(poses);
  summary.initial_cost = cost;
  Linearization lin;
  bool stale = true;  // lin is not at `poses`: linearize only when it is used
  const Eigen::Index free = 6 * static_cast<Eigen::Index>(poses.size()) - 6;  // frame 0 fixed
  double mu = settings.initial_damping;
  double nu = 2.0;
  bool settled_step = false;  // the last step taken gained at most the tolerance

  while (free > 0 && summary.iterations < settings.max_iterations && cost > 0.0) {
    if (stale) {
      lin = problem.linearize(poses);
      prior.addTo(lin, poses);
      stale = false;
    }
    const Eigen::MatrixXd H = lin.hessian.bottomRightCorner(free, free);
    const Eigen::VectorXd g = lin.gradient.tail(free);
    if (!(g.lpNorm<Eigen::Infinity>() > 0.0)) break;  // stationary
    ++summary.iterations;

    Eigen::MatrixXd damped = H;
    damped.diagonal() += mu * dampingScale(H);
    // Blocked Cholesky: about twice as fast as LDLT on a top-layer system
    // (~1800 unknowns), and it refuses an indefinite damped system (far from
    // the optimum the exact Hessian can be), which then just raises mu.
    const Eigen::LLT<Eigen::MatrixXd> cholesky(damped);
    Eigen::VectorXd step = -cholesky.solve(g);
    const double predicted = -(g.dot(step) + 0.5 * step.dot(H * step));

    bool accepted = false;
    if (cholesky.info() == Eigen::Success && isFinite(step) && predicted > 0.0) {
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(free + 6);
      delta.tail(free) = step;
      std::vector<Pose> trial = applyUpdate(poses, delta);
      const double trial_cost = objective(trial);
      if (trial_cost < cost) {  // never accept a step that raises the cost
        const double gain = cost - trial_cost;
        const double rho = gain / predicted;
        mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));  // Nielsen
        nu = 2.0;
        poses = std::move(trial);
        const double previous = cost;
        cost = trial_cost;
        stale = true;
        ++summary.accepted_steps;
        accepted = true;
        if (gain <= settings.relative_cost_tolerance * previous) {  // settled
          settled_step = true;
          break;
        }
      }
    }
    if (!accepted) {
      mu *= nu;
      nu *= 2.0;
      if (mu > kMaxDamping) break;  // no descent found even with tiny steps
    }
  }
  summary.final_cost = cost;
  if (settled != nullptr) *settled = stale && !settled_step ? Linearization{} : std::move(lin);
  return summary;
}

}  // namespace hba::ba
