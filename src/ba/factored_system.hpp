#pragma once
// The refinement's linearized objective, kept factored (never formed as a
// 6K x 6K matrix): per frame the gradient and the 6x6 diagonal block, per
// observation (a frame's cluster of one plane) the 3x6 block of its plane's
// Z, per plane the weights, so that H = blockdiag(D) + sum_p Z_p^T W_p Z_p
// + the motion prior's blocks. See plane_cost.hpp for Z, W and D.
// Every sum is taken in fixed chunks added in order: the same bits for any
// thread count, and for a problem spread over a group's processes, each
// summing its own chunks (plane_spread.hpp).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/StdVector>

#include "hba/ba/motion_prior.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/ba/position_prior.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

using Mat6List = std::vector<Mat6, Eigen::aligned_allocator<Mat6>>;

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

  ObservationIndex(const PlaneProblem& problem, std::size_t frames);
};

class FactoredSystem {
 public:
  FactoredSystem(const PlaneProblem& problem, const MotionPrior& prior, const PositionPriors& positions,
                 const ObservationIndex& index, const std::vector<Pose>& poses);

  // H over frames [first, K) (first = 1 leaves the held frame 0 out), its
  // upper triangle only (the diagonal blocks whole, the rest below zero):
  // what a Cholesky factorization reads, for half the products.
  Eigen::MatrixXd upperTriangle(std::size_t first = 0) const;
  // H itself (6K x 6K), from upperTriangle(): for tests.
  Eigen::MatrixXd dense() const;

  double cost() const { return cost_; }
  const Eigen::VectorXd& gradient() const { return gradient_; }
  // The 6x6 diagonal block of frame i of H (for the preconditioner).
  Mat6 block(std::size_t i) const { return diagonal_[i] + own_[i]; }
  std::size_t frames() const { return frames_; }

  // y = H x, in one pass over the observations.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

 private:
  // A prior term's Gauss-Newton blocks between frames a and b.
  struct PriorBlock {
    std::size_t a = 0;
    std::size_t b = 0;
    Mat6 ab = Mat6::Zero();
  };
  Eigen::Map<const Eigen::Matrix<float, 3, 6, Eigen::RowMajor>> z(std::size_t k) const {
    return Eigen::Map<const Eigen::Matrix<float, 3, 6, Eigen::RowMajor>>(&z_[18 * k]);
  }

  const ObservationIndex& index_;
  // The chunks the sums are taken in, and this process's (all of them
  // unless the problem is spread over a group).
  PlaneSpread spread_;
  std::size_t frames_ = 0;
  // 3x6 per observation, rows contiguous. Not zeroed: every entry is
  // written by the parallel linearization, which then also takes the pages
  // the system first touches (hundreds of MB in a refinement block, which
  // zeroing touched on one thread, each LM step).
  std::unique_ptr<float[]> z_;
  std::vector<Eigen::Vector3f> weights_;
  std::vector<PriorBlock> prior_;
  Eigen::VectorXd gradient_;
  Mat6List diagonal_;  // per frame: the planes' D blocks and the prior's
  Mat6List own_;       // per frame: sum of Z_a^T W Z_a (in H x through the planes)
  double cost_ = 0.0;
};

}  // namespace hba::ba
