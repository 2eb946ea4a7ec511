#include "hba/ba/sparse_lm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "factored_system.hpp"

namespace hba::ba {
namespace {

// Marquardt scale of each unknown (its own curvature, with a floor).
Eigen::VectorXd dampingScale(const FactoredSystem& system) {
  Eigen::VectorXd d(6 * static_cast<Eigen::Index>(system.frames()));
  for (std::size_t i = 0; i < system.frames(); ++i) d.segment<6>(6 * i) = system.block(i).diagonal();
  d = d.cwiseMax(0.0);
  const double floor = std::max(1e-9 * d.maxCoeff(), 1e-12);
  return d.cwiseMax(floor);
}

// Solves (H + mu D) x = -g for every frame (but frame 0 when it is held)
// by factoring it, from H's upper triangle over those frames; zero if the
// damped matrix is not positive definite.
Eigen::VectorXd solveDampedDense(const Eigen::MatrixXd& upper, const Eigen::VectorXd& gradient,
                                 const Eigen::VectorXd& scale, double mu) {
  const Eigen::Index n = upper.rows();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(gradient.size());
  if (n <= 0) return x;
  Eigen::MatrixXd A = upper;
  A.diagonal() += mu * scale.tail(n);
  const Eigen::LLT<Eigen::MatrixXd, Eigen::Upper> llt(A);
  if (llt.info() == Eigen::Success) x.tail(n) = llt.solve(-gradient.tail(n));
  return x;
}

// Solves (H + mu D) x = -g for every frame (but frame 0 when it is held) by preconditioned
// conjugate gradients; stops early at negative curvature (far from the
// optimum the exact Hessian can be indefinite) with the last good iterate.
Eigen::VectorXd solveDamped(const FactoredSystem& system, const Eigen::VectorXd& scale, double mu,
                            const SparseLmSettings& settings, int& products) {
  const Eigen::Index n = system.gradient().size();
  const std::size_t frames = system.frames();
  auto gauge = [&](Eigen::VectorXd& v) {
    if (settings.hold_first) v.head<6>().setZero();
  };
  auto apply = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd out = system.multiply(v) + mu * scale.cwiseProduct(v);
    gauge(out);
    return out;
  };
  // Block-Jacobi preconditioner: the damped 6x6 blocks, inverted.
  Mat6List inverse(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    Mat6 block = system.block(i);
    block.diagonal() += mu * scale.segment<6>(6 * i);
    inverse[i] = positiveInverse(block);
  }
  auto precondition = [&](const Eigen::VectorXd& r) {
    Eigen::VectorXd z(n);
    for (std::size_t i = 0; i < frames; ++i) z.segment<6>(6 * i) = inverse[i] * r.segment<6>(6 * i);
    gauge(z);
    return z;
  };

  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r = -system.gradient();
  gauge(r);
  Eigen::VectorXd z = precondition(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  const double r0 = r.norm();
  for (int k = 0; k < settings.cg_max_iterations && r.norm() > settings.cg_relative_tolerance * r0; ++k) {
    const Eigen::VectorXd Ap = apply(p);
    ++products;
    const double curvature = p.dot(Ap);
    if (!(curvature > 0.0)) {
      if (k == 0) x = z;  // at least the preconditioned steepest descent
      break;
    }
    const double alpha = rz / curvature;
    x += alpha * p;
    r -= alpha * Ap;
    z = precondition(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return x;
}

}  // namespace

// The exact Hessian's blocks can be indefinite far from the optimum:
// inverting their clamped diagonal instead gave huge preconditioned steps
// that only the step cap stopped, and left the result to rounding.
Mat6 positiveInverse(const Mat6& block) {
  const Eigen::LDLT<Mat6> ldlt(block);
  if (ldlt.info() == Eigen::Success && ldlt.isPositive()) {
    const Vec6 pivots = ldlt.vectorD();
    if (pivots.minCoeff() > 1e-9 * pivots.maxCoeff()) return ldlt.solve(Mat6::Identity());
  }
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(block);
  const Vec6 magnitude = eig.eigenvalues().cwiseAbs();
  const double floor = std::max(1e-9 * magnitude.maxCoeff(), 1e-300);
  return eig.eigenvectors() * magnitude.cwiseMax(floor).cwiseInverse().asDiagonal() *
         eig.eigenvectors().transpose();
}

LmSummary solveSparseLevenbergMarquardt(const PlaneProblem& problem, std::vector<Pose>& poses,
                                        const SparseLmSettings& settings, const MotionPrior& prior,
                                        const PositionPriors& positions,
                                        std::optional<double> start_plane_cost) {
  auto objective = [&](const std::vector<Pose>& at) {
    return problem.cost(at) + prior.cost(at) + positions.cost(at);
  };
  const ObservationIndex index(problem, poses.size());

  // Where the priors fix the frame, their best rigid move of the whole is
  // taken exactly before each linearization (see bestRigidMove).
  const bool rigid_moves = !settings.hold_first && !positions.empty();
  auto moveRigidly = [&](std::vector<Pose>& at, double& at_cost) {
    if (!rigid_moves) return;
    const Pose move = positions.bestRigidMove(at);
    std::vector<Pose> moved = at;
    for (Pose& pose : moved) pose = move * pose;
    const double moved_cost = objective(moved);
    if (moved_cost < at_cost) {
      at = std::move(moved);
      at_cost = moved_cost;
    }
  };
  LmSummary summary;
  double cost =
      start_plane_cost ? *start_plane_cost + prior.cost(poses) + positions.cost(poses) : objective(poses);
  summary.initial_cost = cost;
  moveRigidly(poses, cost);
  double mu = settings.initial_damping;
  double nu = 2.0;
  std::unique_ptr<FactoredSystem> system;
  const bool dense = poses.size() <= settings.dense_max_frames;
  Eigen::MatrixXd upper;  // of `system`, when dense
  while (poses.size() > 1 && summary.iterations < settings.max_iterations && cost > 0.0) {
    if (!system) {
      system = std::make_unique<FactoredSystem>(problem, prior, positions, index, poses);
      if (dense) upper = system->upperTriangle(settings.hold_first ? 1 : 0);
    }
    Eigen::VectorXd g = system->gradient();
    if (settings.hold_first) g.head<6>().setZero();
    if (!(g.lpNorm<Eigen::Infinity>() > 0.0)) break;  // stationary
    ++summary.iterations;

    const Eigen::VectorXd scale = dampingScale(*system);
    Eigen::VectorXd step = dense ? solveDampedDense(upper, g, scale, mu)
                                 : solveDamped(*system, scale, mu, settings, summary.cg_products);
    double largest = 0.0;  // of the step, relative to the caps
    for (std::size_t i = 0; i < poses.size(); ++i) {
      largest = std::max({largest, step.segment<3>(6 * i).norm() / settings.max_step_m,
                          step.segment<3>(6 * i + 3).norm() * 180.0 / M_PI / settings.max_step_deg});
    }
    if (largest > 1.0) step /= largest;
    const double predicted = -(g.dot(step) + 0.5 * step.dot(system->multiply(step)));
    bool accepted = false;
    if (step.allFinite() && predicted > 0.0) {
      std::vector<Pose> trial = applyUpdate(poses, step);
      const double trial_cost = objective(trial);
      if (trial_cost < cost) {
        const double gain = cost - trial_cost;
        mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * gain / predicted - 1.0, 3));
        nu = 2.0;
        poses = std::move(trial);
        const double previous = cost;
        cost = trial_cost;
        moveRigidly(poses, cost);
        system.reset();
        ++summary.accepted_steps;
        accepted = true;
        if (gain <= settings.relative_cost_tolerance * previous || gain < settings.min_step_gain) break;
      }
    }
    if (!accepted) {
      mu *= nu;
      nu *= 2.0;
      if (mu > 1e12) break;
    }
  }
  summary.final_cost = cost;
  return summary;
}

}  // namespace hba::ba
