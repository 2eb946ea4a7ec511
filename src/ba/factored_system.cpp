#include "factored_system.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "dist/bytes.hpp"
#include "hba/core/error.hpp"
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

// One chunk of planes' sums: the cost, then per frame its gradient (6),
// diagonal block (36) and own block (36), in one array that a group's
// members send each other as it is.
class FrameSums {
 public:
  explicit FrameSums(std::size_t frames) : values_(1 + kPerFrame * frames, 0.0) {}
  explicit FrameSums(std::vector<double> values) : values_(std::move(values)) {}
  double& cost() { return values_[0]; }
  double cost() const { return values_[0]; }
  Eigen::Map<Vec6> gradient(std::size_t i) { return Eigen::Map<Vec6>(at(i)); }
  Eigen::Map<Mat6> diagonal(std::size_t i) { return Eigen::Map<Mat6>(at(i) + 6); }
  Eigen::Map<Mat6> own(std::size_t i) { return Eigen::Map<Mat6>(at(i) + 42); }
  Eigen::Map<const Vec6> gradient(std::size_t i) const { return Eigen::Map<const Vec6>(at(i)); }
  Eigen::Map<const Mat6> diagonal(std::size_t i) const { return Eigen::Map<const Mat6>(at(i) + 6); }
  Eigen::Map<const Mat6> own(std::size_t i) const { return Eigen::Map<const Mat6>(at(i) + 42); }
  std::vector<double> take() { return std::move(values_); }

 private:
  static constexpr std::size_t kPerFrame = 6 + 36 + 36;
  double* at(std::size_t i) { return values_.data() + 1 + kPerFrame * i; }
  const double* at(std::size_t i) const { return values_.data() + 1 + kPerFrame * i; }
  std::vector<double> values_;
};

// Every chunk's partial, in chunk order: this member's own (`mine`, for
// its chunks) and, when the problem is spread, the others' as they sent
// them. The sums then add them in order, as one process does.
template <typename T>
std::vector<std::vector<T>> allChunks(const PlaneSpread& spread, std::vector<std::vector<T>> mine) {
  if (!spread.spread()) return mine;
  dist::ByteWriter writer;
  for (const std::vector<T>& part : mine) writer.putVector(part);
  std::vector<std::vector<T>> all;
  for (const dist::Bytes& bytes : spread.group->allGather(writer.take())) {
    dist::ByteReader reader(bytes);
    while (!reader.done()) all.push_back(reader.getVector<T>());
  }
  if (all.size() + 1 != spread.chunk_begin.size()) {
    throw Error("refinement: the group's members sent " + std::to_string(all.size()) + " chunks of " +
                std::to_string(spread.chunk_begin.size() - 1));
  }
  return all;
}

}  // namespace

FactoredSystem::FactoredSystem(const PlaneProblem& problem, const MotionPrior& prior,
                               const PositionPriors& positions, const ObservationIndex& index,
                               const std::vector<Pose>& poses)
    : index_(index), spread_(problem.spread()), frames_(poses.size()) {
  const FrameTransforms transforms(poses);
  const std::size_t planes = problem.numPlanes();
  if (!spread_.group) {  // one process: all the chunks, of all the planes
    spread_.chunk_begin = sumChunks(index.plane_begin, frames_);
    spread_.end_chunk = spread_.chunk_begin.size() - 1;
  }
  z_.reset(new float[18 * index.frame_of.size()]);
  weights_.resize(planes);
  gradient_.setZero(6 * static_cast<Eigen::Index>(frames_));
  diagonal_.assign(frames_, Mat6::Zero());
  own_.assign(frames_, Mat6::Zero());
  // Planes linearized in parallel chunks, each summing into its own
  // per-frame gradient and blocks (16 MB in all); the chunks are then
  // added in order (deterministic). No plane's full linearization is kept.
  std::vector<std::vector<double>> mine(spread_.end_chunk - spread_.first_chunk);
  tbb::parallel_for(std::size_t{0}, mine.size(), [&](std::size_t k) {
    FrameSums sums(frames_);
    thread_local PlaneTerms terms;
    const std::size_t c = spread_.first_chunk + k;
    for (std::size_t p = spread_.chunk_begin[c] - spread_.firstPlane();
         p < spread_.chunk_begin[c + 1] - spread_.firstPlane(); ++p) {
      planeTerms(problem.planes()[p], transforms, terms);
      weights_[p] = terms.weights.cast<float>();
      sums.cost() += terms.cost;
      const std::size_t first = index.plane_begin[p];
      const auto& clusters = problem.planes()[p].clusters;
      for (std::size_t a = 0; a < clusters.size(); ++a) {
        const std::size_t i = clusters[a].frame;
        const Eigen::Matrix<double, 3, 6>& Za = terms.z[a];
        Eigen::Map<Eigen::Matrix<float, 3, 6, Eigen::RowMajor>> stored(&z_[18 * (first + a)]);
        stored = Za.cast<float>();
        sums.gradient(i) += terms.gradient[a];
        sums.diagonal(i) += terms.diagonal[a];
        sums.own(i).noalias() += Za.transpose() * terms.weights.asDiagonal() * Za;
      }
    }
    mine[k] = sums.take();
  });
  for (std::vector<double>& values : allChunks(spread_, std::move(mine))) {
    const FrameSums sums(std::move(values));
    cost_ += sums.cost();
    for (std::size_t i = 0; i < frames_; ++i) {
      gradient_.segment<6>(6 * static_cast<Eigen::Index>(i)) += sums.gradient(i);
      diagonal_[i] += sums.diagonal(i);
      own_[i] += sums.own(i);
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
  if (spread_.spread()) throw Error("refinement: the dense solve of a problem spread over processes");
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
  std::vector<std::vector<float>> mine(spread_.end_chunk - spread_.first_chunk);
  tbb::parallel_for(std::size_t{0}, mine.size(), [&](std::size_t k) {
    std::vector<float>& out = mine[k];
    out.assign(static_cast<std::size_t>(n), 0.0f);
    const std::size_t c = spread_.first_chunk + k;
    for (std::size_t p = spread_.chunk_begin[c] - spread_.firstPlane();
         p < spread_.chunk_begin[c + 1] - spread_.firstPlane(); ++p) {
      const std::uint32_t k0 = index_.plane_begin[p];
      const std::uint32_t k1 = index_.plane_begin[p + 1];
      // Each row of Z as 4 + 2 floats, the 4 in one SIMD register: Z x
      // summed lane by lane over the plane's observations (added up once),
      // Z^T w as three rows scaled and added.
      Eigen::Vector4f head[3] = {Eigen::Vector4f::Zero(), Eigen::Vector4f::Zero(), Eigen::Vector4f::Zero()};
      Eigen::Vector2f tail[3] = {Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero()};
      for (std::uint32_t o = k0; o < k1; ++o) {
        const float* zk = &z_[18 * std::size_t{o}];
        const float* xk = xf.data() + 6 * std::size_t{index_.frame_of[o]};
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
      for (std::uint32_t o = k0; o < k1; ++o) {
        const float* zk = &z_[18 * std::size_t{o}];
        float* yk = out.data() + 6 * std::size_t{index_.frame_of[o]};
        Eigen::Map<Eigen::Vector4f>(yk) += wz(0) * Eigen::Map<const Eigen::Vector4f>(zk) +
                                           wz(1) * Eigen::Map<const Eigen::Vector4f>(zk + 6) +
                                           wz(2) * Eigen::Map<const Eigen::Vector4f>(zk + 12);
        Eigen::Map<Eigen::Vector2f>(yk + 4) += wz(0) * Eigen::Map<const Eigen::Vector2f>(zk + 4) +
                                               wz(1) * Eigen::Map<const Eigen::Vector2f>(zk + 10) +
                                               wz(2) * Eigen::Map<const Eigen::Vector2f>(zk + 16);
      }
    }
  });
  const std::vector<std::vector<float>> partial = allChunks(spread_, std::move(mine));
  Eigen::VectorXd y(n);
  tbb::parallel_for(std::size_t{0}, frames_, [&](std::size_t i) {
    Eigen::Matrix<float, 6, 1> sum = Eigen::Matrix<float, 6, 1>::Zero();
    for (const std::vector<float>& part : partial)
      sum += Eigen::Map<const Eigen::Matrix<float, 6, 1>>(&part[6 * i]);
    y.segment<6>(6 * i) = diagonal_[i] * x.segment<6>(6 * i) + sum.cast<double>();
  });
  for (const PriorBlock& block : prior_) {
    y.segment<6>(6 * block.a) += block.ab * x.segment<6>(6 * block.b);
    y.segment<6>(6 * block.b) += block.ab.transpose() * x.segment<6>(6 * block.a);
  }
  return y;
}

}  // namespace hba::ba
