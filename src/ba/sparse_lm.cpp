#include "hba/ba/sparse_lm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <tbb/parallel_for.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "hba/core/relative_pose_error.hpp"

namespace hba::ba {
namespace {

using Mat6List = std::vector<Mat6, Eigen::aligned_allocator<Mat6>>;

// A prior term's Gauss-Newton blocks between frames a and b.
struct PriorBlock {
  std::size_t a = 0;
  std::size_t b = 0;
  Mat6 ab = Mat6::Zero();
};

// Where the observations (frame, plane) are: in plane order, and for each
// frame the list of its observations (compressed rows), built once per
// association.
struct ObservationIndex {
  std::vector<std::uint32_t> plane_begin;  // observations of plane p: [plane_begin[p], plane_begin[p+1])
  std::vector<std::uint32_t> frame_of;     // per observation
  std::vector<std::uint32_t>
      frame_begin;                      // observations of frame i: uses[frame_begin[i] .. frame_begin[i+1])
  std::vector<std::uint32_t> uses;      // observation indices, in plane order within a frame
  std::vector<std::uint32_t> plane_of;  // per observation

  ObservationIndex(const PlaneProblem& problem, std::size_t frames) {
    plane_begin.push_back(0);
    for (std::size_t p = 0; p < problem.numPlanes(); ++p) {
      for (const FrameCluster& fc : problem.planes()[p].clusters) {
        frame_of.push_back(fc.frame);
        plane_of.push_back(static_cast<std::uint32_t>(p));
      }
      plane_begin.push_back(static_cast<std::uint32_t>(frame_of.size()));
    }
    frame_begin.assign(frames + 1, 0);
    for (const std::uint32_t f : frame_of) ++frame_begin[f + 1];
    for (std::size_t i = 0; i < frames; ++i) frame_begin[i + 1] += frame_begin[i];
    uses.resize(frame_of.size());
    std::vector<std::uint32_t> next(frame_begin.begin(), frame_begin.end() - 1);
    for (std::uint32_t k = 0; k < frame_of.size(); ++k) uses[next[frame_of[k]]++] = k;
  }
};

// Plane ranges of about equal observation counts, each summing into its
// own partial result of `partial_bytes`: enough for two cores to share (up
// to 64), few enough that the partials stay within `budget` bytes and a
// chunk holds at least a few thousand observations. Depends on the sizes
// only, so sums taken chunk by chunk in order are the same for any thread
// count.
std::vector<std::size_t> planeChunks(const ObservationIndex& index, std::size_t planes,
                                     std::size_t partial_bytes, std::size_t budget) {
  const std::size_t observations = index.frame_of.size();
  const std::size_t by_memory = budget / std::max<std::size_t>(partial_bytes, 1);
  const std::size_t chunks =
      std::clamp<std::size_t>(std::min({std::size_t{64}, by_memory, observations / 4096}), 1, 64);
  std::vector<std::size_t> begin{0};
  for (std::size_t c = 1; c < chunks; ++c) {
    const std::size_t target = observations * c / chunks;
    // The first plane whose observations start at or after the target.
    const auto it = std::lower_bound(index.plane_begin.begin() + static_cast<long>(begin.back()),
                                     index.plane_begin.begin() + static_cast<long>(planes), target);
    begin.push_back(static_cast<std::size_t>(it - index.plane_begin.begin()));
  }
  begin.push_back(planes);
  return begin;
}

// One chunk of planes' sums per frame.
struct FrameSums {
  double cost = 0.0;
  Eigen::VectorXd gradient;
  Mat6List diagonal;
  Mat6List own;
};

// The linearized objective at one set of poses, kept factored: per frame
// the gradient and the 6x6 diagonal block, per observation the 3x6 block of
// its plane's Z (single precision, flat: it only feeds the conjugate-
// gradient products), per plane the weights.
class FactoredSystem {
 public:
  FactoredSystem(const PlaneProblem& problem, const MotionPrior& prior, const PositionPriors& positions,
                 const ObservationIndex& index, const std::vector<Pose>& poses)
      : index_(index), frames_(poses.size()) {
    const FrameTransforms transforms(poses);
    const std::size_t planes = problem.numPlanes();
    // H x sums 6 floats a frame per chunk (16 MB in all).
    chunk_begin_ = planeChunks(index, planes, 6 * sizeof(float) * frames_, std::size_t{16} << 20);
    z_.resize(18 * index.frame_of.size());
    weights_.resize(planes);
    gradient_.setZero(6 * static_cast<Eigen::Index>(frames_));
    diagonal_.assign(frames_, Mat6::Zero());
    own_.assign(frames_, Mat6::Zero());
    // Planes linearized in parallel chunks, each summing into its own
    // per-frame gradient and blocks (16 MB in all); the chunks are then
    // added in order (deterministic). No plane's full linearization is kept.
    const std::vector<std::size_t> build =
        planeChunks(index, planes, frames_ * (sizeof(Vec6) + 2 * sizeof(Mat6)), std::size_t{16} << 20);
    std::vector<FrameSums> partial(build.size() - 1);
    tbb::parallel_for(std::size_t{0}, partial.size(), [&](std::size_t c) {
      FrameSums& sums = partial[c];
      sums.gradient.setZero(6 * static_cast<Eigen::Index>(frames_));
      sums.diagonal.assign(frames_, Mat6::Zero());
      sums.own.assign(frames_, Mat6::Zero());
      thread_local PlaneTerms terms;
      for (std::size_t p = build[c]; p < build[c + 1]; ++p) {
        planeTerms(problem.planes()[p], transforms, terms);
        weights_[p] = terms.weights.cast<float>();
        sums.cost += terms.cost;
        const std::size_t first = index.plane_begin[p];
        const auto& clusters = problem.planes()[p].clusters;
        for (std::size_t a = 0; a < clusters.size(); ++a) {
          const std::size_t i = clusters[a].frame;
          const Eigen::Matrix<double, 3, 6>& Za = terms.z[a];
          Eigen::Map<Eigen::Matrix<float, 3, 6>> stored(&z_[18 * (first + a)]);
          stored = Za.cast<float>();
          sums.gradient.segment<6>(6 * static_cast<Eigen::Index>(i)) += terms.gradient[a];
          sums.diagonal[i] += terms.diagonal[a];
          sums.own[i].noalias() += Za.transpose() * terms.weights.asDiagonal() * Za;
        }
      }
    });
    for (const FrameSums& sums : partial) {
      cost_ += sums.cost;
      gradient_ += sums.gradient;
      for (std::size_t i = 0; i < frames_; ++i) {
        diagonal_[i] += sums.diagonal[i];
        own_[i] += sums.own[i];
      }
    }
    for (const RelativePosePrior& term : prior.terms()) {
      const RelativePoseErrorJacobians J =
          relativePoseErrorJacobians(term.measurement, poses[term.from], poses[term.to]);
      cost_ += J.error.dot(term.weight * J.error);
      gradient_.segment<6>(6 * term.from) += 2.0 * J.d_from.transpose() * term.weight * J.error;
      gradient_.segment<6>(6 * term.to) += 2.0 * J.d_to.transpose() * term.weight * J.error;
      diagonal_[term.from] += 2.0 * J.d_from.transpose() * term.weight * J.d_from;
      diagonal_[term.to] += 2.0 * J.d_to.transpose() * term.weight * J.d_to;
      prior_.push_back({term.from, term.to, 2.0 * J.d_from.transpose() * term.weight * J.d_to});
    }
    // Position priors touch one frame each: the diagonal blocks only.
    for (const PositionTerm& term : positions.terms()) {
      const Vec3 e = PositionPriors::error(term, poses[term.frame]);
      const Eigen::Matrix<double, 3, 6> J = PositionPriors::jacobian(term, poses[term.frame]);
      cost_ += e.dot(term.weight * e);
      gradient_.segment<6>(6 * term.frame) += 2.0 * J.transpose() * term.weight * e;
      diagonal_[term.frame] += 2.0 * J.transpose() * term.weight * J;
    }
  }

  // H itself (6K x 6K): the frames' diagonal blocks, every plane's
  // Z^T W Z and the prior's off-diagonal blocks. Row blocks in parallel,
  // each written by one thread.
  Eigen::MatrixXd dense() const {
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(frames_);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    tbb::parallel_for(std::size_t{0}, frames_, [&](std::size_t i) {
      const auto row = static_cast<Eigen::Index>(6 * i);
      H.block<6, 6>(row, row) += diagonal_[i];
      for (std::uint32_t u = index_.frame_begin[i]; u < index_.frame_begin[i + 1]; ++u) {
        const std::uint32_t k = index_.uses[u];
        const std::uint32_t p = index_.plane_of[k];
        const Eigen::Matrix<float, 6, 3> left =
            Eigen::Map<const Eigen::Matrix<float, 3, 6>>(&z_[18 * k]).transpose() * weights_[p].asDiagonal();
        for (std::uint32_t l = index_.plane_begin[p]; l < index_.plane_begin[p + 1]; ++l) {
          const auto col = static_cast<Eigen::Index>(6 * index_.frame_of[l]);
          H.block<6, 6>(row, col) +=
              (left * Eigen::Map<const Eigen::Matrix<float, 3, 6>>(&z_[18 * l])).cast<double>();
        }
      }
    });
    for (const PriorBlock& block : prior_) {
      H.block<6, 6>(6 * static_cast<Eigen::Index>(block.a), 6 * static_cast<Eigen::Index>(block.b)) +=
          block.ab;
      H.block<6, 6>(6 * static_cast<Eigen::Index>(block.b), 6 * static_cast<Eigen::Index>(block.a)) +=
          block.ab.transpose();
    }
    return H;
  }

  double cost() const { return cost_; }
  const Eigen::VectorXd& gradient() const { return gradient_; }
  // The 6x6 diagonal block of frame i of H (for the preconditioner).
  Mat6 block(std::size_t i) const { return diagonal_[i] + own_[i]; }
  std::size_t frames() const { return frames_; }

  // y = H x = blockdiag(D) x + sum over planes Z^T W Z x, in one pass over
  // the observations (they are the bulk of the memory, read once a
  // product). Planes are cut into fixed chunks, each summing into its own
  // vector; the chunks are then added in order: the same result for any
  // thread count.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const {
    const Eigen::VectorXf xf = x.cast<float>();
    const auto n = static_cast<Eigen::Index>(6 * frames_);
    const std::size_t chunks = chunk_begin_.size() - 1;
    std::vector<Eigen::VectorXf> partial(chunks);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      Eigen::VectorXf& out = partial[c];
      out.setZero(n);
      for (std::size_t p = chunk_begin_[c]; p < chunk_begin_[c + 1]; ++p) {
        const std::uint32_t k0 = index_.plane_begin[p];
        const std::uint32_t k1 = index_.plane_begin[p + 1];
        Eigen::Vector3f z = Eigen::Vector3f::Zero();
        for (std::uint32_t k = k0; k < k1; ++k) {
          z.noalias() += Eigen::Map<const Eigen::Matrix<float, 3, 6>>(&z_[18 * k]) *
                         xf.segment<6>(6 * index_.frame_of[k]);
        }
        const Eigen::Vector3f wz = weights_[p].cwiseProduct(z);
        for (std::uint32_t k = k0; k < k1; ++k) {
          out.segment<6>(6 * index_.frame_of[k]).noalias() +=
              Eigen::Map<const Eigen::Matrix<float, 3, 6>>(&z_[18 * k]).transpose() * wz;
        }
      }
    });
    Eigen::VectorXd y(n);
    tbb::parallel_for(std::size_t{0}, frames_, [&](std::size_t i) {
      Eigen::Matrix<float, 6, 1> sum = Eigen::Matrix<float, 6, 1>::Zero();
      for (const Eigen::VectorXf& part : partial) sum += part.segment<6>(6 * i);
      y.segment<6>(6 * i) = diagonal_[i] * x.segment<6>(6 * i) + sum.cast<double>();
    });
    for (const PriorBlock& block : prior_) {
      y.segment<6>(6 * block.a) += block.ab * x.segment<6>(6 * block.b);
      y.segment<6>(6 * block.b) += block.ab.transpose() * x.segment<6>(6 * block.a);
    }
    return y;
  }

 private:
  const ObservationIndex& index_;
  std::size_t frames_ = 0;
  std::vector<std::size_t> chunk_begin_;  // planes of chunk c: [chunk_begin_[c], chunk_begin_[c+1])
  std::vector<float> z_;                  // 3x6 column-major per observation
  std::vector<Eigen::Vector3f> weights_;
  std::vector<PriorBlock> prior_;
  Eigen::VectorXd gradient_;
  Mat6List diagonal_;  // per frame: the planes' D blocks and the prior's
  Mat6List own_;       // per frame: sum of Z_a^T W Z_a (in H x through the planes)
  double cost_ = 0.0;
};

// Marquardt scale of each unknown (its own curvature, with a floor).
Eigen::VectorXd dampingScale(const FactoredSystem& system) {
  Eigen::VectorXd d(6 * static_cast<Eigen::Index>(system.frames()));
  for (std::size_t i = 0; i < system.frames(); ++i) d.segment<6>(6 * i) = system.block(i).diagonal();
  d = d.cwiseMax(0.0);
  const double floor = std::max(1e-9 * d.maxCoeff(), 1e-12);
  return d.cwiseMax(floor);
}

// Solves (H + mu D) x = -g for every frame (but frame 0 when it is held)
// by factoring it; zero if the damped matrix is not positive definite.
Eigen::VectorXd solveDampedDense(const Eigen::MatrixXd& H, const Eigen::VectorXd& gradient,
                                 const Eigen::VectorXd& scale, double mu, bool hold_first) {
  const Eigen::Index n = H.rows() - (hold_first ? 6 : 0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(H.rows());
  if (n <= 0) return x;
  Eigen::MatrixXd A = H.bottomRightCorner(n, n);
  A.diagonal() += mu * scale.tail(n);
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() == Eigen::Success) x.tail(n) = llt.solve(-gradient.tail(n));
  return x;
}

// Solves (H + mu D) x = -g for every frame (but frame 0 when it is held) by preconditioned
// conjugate gradients; stops early at negative curvature (far from the
// optimum the exact Hessian can be indefinite) with the last good iterate.
Eigen::VectorXd solveDamped(const FactoredSystem& system, const Eigen::VectorXd& scale, double mu,
                            const SparseLmSettings& settings) {
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
                                        const PositionPriors& positions) {
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
  double cost = objective(poses);
  summary.initial_cost = cost;
  moveRigidly(poses, cost);
  double mu = settings.initial_damping;
  double nu = 2.0;
  std::unique_ptr<FactoredSystem> system;
  const bool dense = poses.size() <= settings.dense_max_frames;
  Eigen::MatrixXd H;  // of `system`, when dense
  while (poses.size() > 1 && summary.iterations < settings.max_iterations && cost > 0.0) {
    if (!system) {
      system = std::make_unique<FactoredSystem>(problem, prior, positions, index, poses);
      if (dense) H = system->dense();
    }
    Eigen::VectorXd g = system->gradient();
    if (settings.hold_first) g.head<6>().setZero();
    if (!(g.lpNorm<Eigen::Infinity>() > 0.0)) break;  // stationary
    ++summary.iterations;

    const Eigen::VectorXd scale = dampingScale(*system);
    Eigen::VectorXd step = dense ? solveDampedDense(H, g, scale, mu, settings.hold_first)
                                 : solveDamped(*system, scale, mu, settings);
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
        if (gain <= settings.relative_cost_tolerance * previous) break;
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
