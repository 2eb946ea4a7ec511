#include "factored_system.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "hba/core/relative_pose_error.hpp"

namespace hba::ba {

ObservationIndex::ObservationIndex(const PlaneProblem& problem, std::size_t frames) {
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

namespace {

// Plane ranges of about equal observation counts, each summing into its
// own partial result of `partial_bytes`: enough for two cores to share (up
// to 64), few enough that the partials stay within `budget` bytes and a
// chunk holds at least 16 384 observations (every product zeroes and adds
// up the partials: with 4096, a tenth of nclt's refinement). Depends on the sizes
// only, so sums taken chunk by chunk in order are the same for any thread
// count.
std::vector<std::size_t> planeChunks(const ObservationIndex& index, std::size_t planes,
                                     std::size_t partial_bytes, std::size_t budget) {
  const std::size_t observations = index.frame_of.size();
  const std::size_t by_memory = budget / std::max<std::size_t>(partial_bytes, 1);
  const std::size_t chunks =
      std::clamp<std::size_t>(std::min({std::size_t{64}, by_memory, observations / 16384}), 1, 64);
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

}  // namespace

FactoredSystem::FactoredSystem(const PlaneProblem& problem, const MotionPrior& prior,
                               const PositionPriors& positions, const ObservationIndex& index,
                               const std::vector<Pose>& poses)
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
        Eigen::Map<Eigen::Matrix<float, 3, 6, Eigen::RowMajor>> stored(&z_[18 * (first + a)]);
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

// Columns of frames in parallel, each written by one thread and summed in
// a fixed order (the frame's observations in plane order): the same bits
// for any thread count. Observations of a plane ascend by frame, so the
// blocks above the diagonal of column i come from the plane's observations
// up to frame i's own: half the products of the whole matrix.
Eigen::MatrixXd FactoredSystem::upperTriangle(std::size_t first) const {
  first = std::min(first, frames_);
  // The prior's off-diagonal blocks, by the later frame of their pair.
  std::vector<std::vector<const PriorBlock*>> priors_at(frames_);
  for (const PriorBlock& block : prior_) priors_at[std::max(block.a, block.b)].push_back(&block);
  const auto n = static_cast<Eigen::Index>(6 * (frames_ - first));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  auto at = [&](std::size_t row_frame, std::size_t column_frame) {
    return H.block<6, 6>(static_cast<Eigen::Index>(6 * (row_frame - first)),
                         static_cast<Eigen::Index>(6 * (column_frame - first)));
  };
  tbb::parallel_for(first, frames_, [&](std::size_t i) {
    at(i, i) += diagonal_[i];
    for (std::uint32_t u = index_.frame_begin[i]; u < index_.frame_begin[i + 1]; ++u) {
      const std::uint32_t k = index_.uses[u];
      const std::uint32_t p = index_.plane_of[k];
      const Eigen::Matrix<float, 3, 6> weighted = weights_[p].asDiagonal() * z(k);
      for (std::uint32_t l = index_.plane_begin[p]; l <= k; ++l) {
        const std::uint32_t j = index_.frame_of[l];
        if (j >= first) at(j, i) += (z(l).transpose() * weighted).cast<double>();
      }
    }
    for (const PriorBlock* block : priors_at[i]) {
      const std::size_t j = std::min(block->a, block->b);
      if (j < first || j == i) continue;
      // H(a, b) is `ab`: H(j, i) is it or its transpose.
      at(j, i) += block->a == j ? block->ab : Mat6(block->ab.transpose());
    }
  });
  return H;
}

Eigen::MatrixXd FactoredSystem::dense() const {
  const Eigen::MatrixXd upper = upperTriangle();
  return upper.selfadjointView<Eigen::Upper>();
}

// blockdiag(D) x + sum over planes Z^T W Z x: planes are cut into fixed
// chunks, each summing into its own vector; the chunks are then added in
// order: the same result for any thread count. The observations are the
// bulk of the memory, read once a product.
Eigen::VectorXd FactoredSystem::multiply(const Eigen::VectorXd& x) const {
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
      // Each row of Z as 4 + 2 floats, the 4 in one SIMD register: Z x
      // summed lane by lane over the plane's observations (added up once),
      // Z^T w as three rows scaled and added.
      Eigen::Vector4f head[3] = {Eigen::Vector4f::Zero(), Eigen::Vector4f::Zero(), Eigen::Vector4f::Zero()};
      Eigen::Vector2f tail[3] = {Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero()};
      for (std::uint32_t k = k0; k < k1; ++k) {
        const float* zk = &z_[18 * std::size_t{k}];
        const float* xk = xf.data() + 6 * std::size_t{index_.frame_of[k]};
        const Eigen::Map<const Eigen::Vector4f> x_head(xk);
        const Eigen::Map<const Eigen::Vector2f> x_tail(xk + 4);
        for (int r = 0; r < 3; ++r) {
          head[r] += Eigen::Map<const Eigen::Vector4f>(zk + 6 * r).cwiseProduct(x_head);
          tail[r] += Eigen::Map<const Eigen::Vector2f>(zk + 6 * r + 4).cwiseProduct(x_tail);
        }
      }
      const Eigen::Vector3f zx(head[0].sum() + tail[0].sum(), head[1].sum() + tail[1].sum(),
                               head[2].sum() + tail[2].sum());
      const Eigen::Vector3f wz = weights_[p].cwiseProduct(zx);
      for (std::uint32_t k = k0; k < k1; ++k) {
        const float* zk = &z_[18 * std::size_t{k}];
        float* yk = out.data() + 6 * std::size_t{index_.frame_of[k]};
        Eigen::Map<Eigen::Vector4f>(yk) += wz(0) * Eigen::Map<const Eigen::Vector4f>(zk) +
                                           wz(1) * Eigen::Map<const Eigen::Vector4f>(zk + 6) +
                                           wz(2) * Eigen::Map<const Eigen::Vector4f>(zk + 12);
        Eigen::Map<Eigen::Vector2f>(yk + 4) += wz(0) * Eigen::Map<const Eigen::Vector2f>(zk + 4) +
                                               wz(1) * Eigen::Map<const Eigen::Vector2f>(zk + 10) +
                                               wz(2) * Eigen::Map<const Eigen::Vector2f>(zk + 16);
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

}  // namespace hba::ba
