// The refinement's solver internals: the factored system against the
// formed one, and the conjugate gradients' budget.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "factored_system.hpp"
#include "hba/ba/lm_solver.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/sparse_lm.hpp"
#include "hba/core/lie.hpp"
#include "random_planes.hpp"

namespace hba::ba {
namespace {

// Frames along a 1 m-spaced path, each plane seen by `reach` consecutive
// frames; the start bends away from the truth more with every frame (the
// long, smooth error that block Jacobi resolves slowly).
struct Chain {
  std::vector<Pose> truth;
  std::vector<Pose> start;
  PlaneProblem problem{{}, 0};
};

Chain chain(int frames, int planes, int reach, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Chain c;
  for (int i = 0; i < frames; ++i) {
    c.truth.emplace_back(so3Exp(0.1 * test::randomUnit(rng)), Vec3(i, 0.3 * std::sin(0.1 * i), 0.0));
  }
  std::vector<PlaneObservation> observed;
  for (int p = 0; p < planes; ++p) {
    const auto first = static_cast<std::uint32_t>(p % (frames - reach + 1));
    std::vector<std::uint32_t> seen;
    for (std::uint32_t f = first; f < first + static_cast<std::uint32_t>(reach); ++f) seen.push_back(f);
    // A plane near the frames that see it (randomPlane places it near the
    // world origin: the frames are moved there instead).
    std::vector<Pose> near = c.truth;
    for (Pose& pose : near) pose.t -= c.truth[first].t;
    observed.push_back(test::randomPlane(rng, near, seen, 6, 0.005).observation);
  }
  c.problem = PlaneProblem(std::move(observed), static_cast<std::size_t>(frames));
  c.start = c.truth;
  for (int i = 1; i < frames; ++i) {
    const double s = static_cast<double>(i) / frames;
    c.start[i] = Pose(so3Exp(Vec3(0.0, 0.0, 0.01 * s) + 0.0005 * test::randomUnit(rng)) * c.truth[i].R(),
                      c.truth[i].t + Vec3(0.0, 0.5 * s * s, 0.2 * s) + 0.005 * test::randomUnit(rng));
  }
  return c;
}

// A 40-frame chain's factored system at its start, with the motion prior.
// Its members refer to one another: built in place, never copied.
struct ChainSystem {
  Chain c = chain(40, 600, 6, 3);
  MotionPrior prior = neighbourPrior(c.start, {}, MotionPriorSettings{});
  ObservationIndex index{c.problem, c.start.size()};
  FactoredSystem system{c.problem, prior, {}, index, c.start};

  ChainSystem() = default;
  ChainSystem(const ChainSystem&) = delete;
  ChainSystem& operator=(const ChainSystem&) = delete;
};

// H x from the factored planes equals the formed H times x, and H is
// symmetric (the stored Z are single precision: float rounding).
TEST(FactoredSystem, ProductIsTheFormedMatrixTimesX) {
  const ChainSystem formed;
  const FactoredSystem& system = formed.system;
  const Eigen::MatrixXd H = system.dense();
  EXPECT_LT((H - H.transpose()).norm(), 1e-6 * H.norm());
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd x = Eigen::VectorXd::Random(H.rows());
    EXPECT_LT((system.multiply(x) - H * x).norm(), 1e-5 * (H * x).norm());
  }
  for (std::size_t i = 0; i < formed.c.start.size(); ++i) {
    EXPECT_LT((system.block(i) - H.block<6, 6>(6 * i, 6 * i)).norm(), 1e-5 * H.norm()) << "frame " << i;
  }
}

// The formed upper triangle over the free frames is H (itself checked
// against the factored products above) without the held frame's rows and
// columns, zero below the diagonal blocks (the Cholesky factorization reads
// the upper half; the products below are not taken).
TEST(FactoredSystem, UpperTriangleLeavesTheHeldFrameOut) {
  const ChainSystem formed;
  const FactoredSystem& system = formed.system;
  const Eigen::MatrixXd H = system.dense();
  const Eigen::MatrixXd upper = system.upperTriangle(1);
  const Eigen::Index n = H.rows() - 6;
  ASSERT_EQ(upper.rows(), n);
  ASSERT_EQ(upper.cols(), n);
  const Eigen::MatrixXd expected = H.bottomRightCorner(n, n);
  EXPECT_LT((Eigen::MatrixXd(upper.triangularView<Eigen::Upper>()) -
             Eigen::MatrixXd(expected.triangularView<Eigen::Upper>()))
                .norm(),
            1e-12 * H.norm());
  for (Eigen::Index b = 6; b < n; b += 6) {
    EXPECT_EQ(upper.block(b, 0, n - b, b).norm(), 0.0) << "below the diagonal block at " << b;
  }
}

// The summary counts the products H x the conjugate gradients take: none
// when the system is formed and factored, at most the cap per step
// otherwise. On a 300-frame chain whose start bends smoothly away from the
// truth, block Jacobi needs hundreds of products for a tight solve (each
// one moves a bend by a few frames), which is why the refinement's steps
// are inexact (docs/ba.md).
TEST(SparseLm, CountsTheProductsOfItsSteps) {
  const Chain c = chain(300, 4000, 10, 4);
  auto oneStep = [&](int cap, std::size_t dense_max_frames, std::vector<Pose>& poses) {
    SparseLmSettings settings;
    settings.max_iterations = 1;
    settings.cg_max_iterations = cap;
    settings.cg_relative_tolerance = 1e-8;
    settings.dense_max_frames = dense_max_frames;
    settings.max_step_m = 10.0;
    poses = c.start;
    const LmSummary s = solveSparseLevenbergMarquardt(c.problem, poses, settings);
    EXPECT_EQ(s.accepted_steps, 1);
    return s;
  };
  std::vector<Pose> exact, tight, capped;
  const LmSummary e = oneStep(50, 300, exact);
  const LmSummary t = oneStep(5000, 0, tight);
  const LmSummary k = oneStep(50, 0, capped);
  std::printf("products of one step to 1e-8: %d (capped run: %d)\n", t.cg_products, k.cg_products);
  EXPECT_EQ(e.cg_products, 0);
  EXPECT_GT(t.cg_products, 100);
  EXPECT_EQ(k.cg_products, 50);
  EXPECT_NEAR(t.final_cost, e.final_cost, 1e-6 * e.initial_cost);  // the tight solve is the exact step
  for (std::size_t i = 0; i < exact.size(); ++i) {
    EXPECT_LT((tight[i].t - exact[i].t).norm(), 1e-4) << "frame " << i;
  }
}

}  // namespace
}  // namespace hba::ba
