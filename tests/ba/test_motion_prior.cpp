#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <cstdio>

#include <random>

#include <tbb/global_control.h>

#include "hba/ba/association.hpp"
#include "hba/ba/lm_solver.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/sparse_lm.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "random_planes.hpp"
#include "synthetic_window.hpp"

namespace hba::ba {
namespace {

using test::makeSyntheticWindow;
using test::relativePoseError;
using test::SyntheticWindowSpec;

std::vector<Pose> randomPoses(std::size_t n, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < n; ++i) {
    poses.emplace_back(Quat(so3Exp(Vec3(g(rng), g(rng), g(rng)) * 0.5)), Vec3(g(rng), g(rng), g(rng)) * 3.0);
  }
  return poses;
}

// The update of window_ba.hpp applied to coordinate k of frame i.
std::vector<Pose> nudge(const std::vector<Pose>& poses, std::size_t i, int k, double h) {
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(poses.size()));
  delta(static_cast<Eigen::Index>(6 * i) + k) = h;
  return applyUpdate(poses, delta);
}

TEST(MotionPrior, VanishesAtTheInputAndGrowsAwayFromIt) {
  std::mt19937 rng(3);
  const std::vector<Pose> input = randomPoses(4, rng);
  const MotionPrior prior = neighbourPrior(input, {}, MotionPriorSettings{});
  ASSERT_EQ(prior.terms().size(), 3u);
  EXPECT_LT(prior.cost(input), 1e-20);
  EXPECT_GT(prior.cost(nudge(input, 2, 0, 0.1)), 0.0);
}

TEST(MotionPrior, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(5);
  const std::vector<Pose> input = randomPoses(4, rng);
  const MotionPrior prior = neighbourPrior(input, {1.0, 2.0, 3.0}, MotionPriorSettings{});
  // Away from the input, where the residuals are not zero.
  std::vector<Pose> poses = input;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    for (int k = 0; k < 6; ++k) poses = nudge(poses, i, k, 0.03 * (k + 1) * (i % 2 ? 1 : -1));
  }
  Linearization lin;
  lin.gradient.setZero(24);
  lin.hessian.setZero(24, 24);
  prior.addTo(lin, poses);
  EXPECT_NEAR(lin.cost, prior.cost(poses), 1e-12);
  const double h = 1e-6;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    for (int k = 0; k < 6; ++k) {
      const double numeric =
          (prior.cost(nudge(poses, i, k, h)) - prior.cost(nudge(poses, i, k, -h))) / (2 * h);
      EXPECT_NEAR(lin.gradient(static_cast<Eigen::Index>(6 * i) + k), numeric,
                  1e-5 * std::max(1.0, std::abs(numeric)));
    }
  }
  // Gauss-Newton Hessian: equals the exact one at zero residual.
  const MotionPrior at_input = neighbourPrior(input, {1.0, 2.0, 3.0}, MotionPriorSettings{});
  Linearization zero;
  zero.gradient.setZero(24);
  zero.hessian.setZero(24, 24);
  at_input.addTo(zero, input);
  const double hh = 1e-4;
  for (std::size_t i = 0; i < input.size(); ++i) {
    for (int k = 0; k < 6; ++k) {
      Linearization plus, minus;
      plus.gradient.setZero(24);
      plus.hessian.setZero(24, 24);
      minus = plus;
      at_input.addTo(plus, nudge(input, i, k, hh));
      at_input.addTo(minus, nudge(input, i, k, -hh));
      const Eigen::VectorXd column = (plus.gradient - minus.gradient) / (2 * hh);
      const Eigen::VectorXd analytic = zero.hessian.col(static_cast<Eigen::Index>(6 * i) + k);
      EXPECT_LT((column - analytic).norm(), 1e-5 * std::max(1.0, analytic.norm()));
    }
  }
}

TEST(MotionPrior, LooserWithThePathBetweenFrames) {
  std::mt19937 rng(7);
  const std::vector<Pose> input = randomPoses(2, rng);
  const MotionPrior near = neighbourPrior(input, {1.0}, MotionPriorSettings{});
  const MotionPrior far = neighbourPrior(input, {100.0}, MotionPriorSettings{});
  EXPECT_GT(near.terms()[0].weight(0, 0), 50.0 * far.terms()[0].weight(0, 0));
  EXPECT_GT(near.terms()[0].weight(3, 3), 10.0 * far.terms()[0].weight(3, 3));
}

// Only the pair whose relative pose moved beyond three sigmas is named: a
// metre between frames 4 and 5 of a straight line 1 m apart (sigma 0.2 m),
// not the 10 cm that the rest of the line moved.
TEST(MotionPrior, NamesThePairsThatSlidBeyondIt) {
  std::vector<Pose> line(10);
  for (std::size_t i = 0; i < line.size(); ++i) line[i].t = Vec3(static_cast<double>(i), 0, 0);
  std::vector<Pose> moved = line;
  for (std::size_t i = 5; i < moved.size(); ++i) moved[i].t.y() += 1.0;
  for (std::size_t i = 0; i < moved.size(); ++i) moved[i].t.z() += 0.1 * static_cast<double>(i % 2);
  const MotionPriorSettings settings;
  EXPECT_EQ(stepsBeyondThePrior(line, moved, {}, settings, 3.0), std::vector<std::size_t>{4});
  EXPECT_TRUE(stepsBeyondThePrior(line, line, {}, settings, 3.0).empty());
  // A turn of 5 degrees between two frames (sigma 1.2 deg) is named too.
  std::vector<Pose> turned = line;
  for (std::size_t i = 7; i < turned.size(); ++i) {
    turned[i].q = Quat(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Vec3::UnitZ()));
  }
  EXPECT_EQ(stepsBeyondThePrior(line, turned, {}, settings, 3.0), std::vector<std::size_t>{6});
}

TEST(MotionPrior, RejectsBadSettingsAndSizes) {
  std::mt19937 rng(9);
  const std::vector<Pose> input = randomPoses(3, rng);
  MotionPriorSettings bad;
  bad.translation_sigma = 0.0;
  EXPECT_THROW(neighbourPrior(input, {}, bad), Error);
  EXPECT_THROW(neighbourPrior(input, {1.0}, MotionPriorSettings{}), Error);
  MotionPriorSettings off;
  off.enabled = false;
  EXPECT_TRUE(neighbourPrior(input, {}, off).empty());
}

// A noisy window: the prior's pull towards a wrong input is far below the
// noise, because thousands of plane points outweigh it.
TEST(MotionPrior, BarelyMovesAWellConstrainedWindow) {
  SyntheticWindowSpec spec;
  spec.noise_sigma = 0.02;
  const auto window = makeSyntheticWindow(spec);
  BaSettings settings = test::patchBaSettings();
  BaSettings without = settings;
  without.motion_prior.enabled = false;
  const BaResult with_prior = optimizeWindow(window.scanPointers(), window.initial, settings);
  const BaResult no_prior = optimizeWindow(window.scanPointers(), window.initial, without);
  const auto gap = relativePoseError(with_prior.poses, no_prior.poses);
  const auto error = relativePoseError(no_prior.poses, window.truth);
  EXPECT_LT(gap.max_translation, 0.5 * error.max_translation + 1e-4);
  EXPECT_LT(relativePoseError(with_prior.poses, window.truth).max_translation, 0.01);
}

// One association of a noisy eight-frame window, its motion prior, and
// the dense LM's optimum on it: what the sparse LM must reach.
struct SparseLmCase {
  test::SyntheticWindow window;
  Association association;
  MotionPrior prior;
  std::vector<Pose> dense;
  LmSummary dense_summary;
};

SparseLmCase sparseLmCase() {
  SyntheticWindowSpec spec;
  spec.frames = 8;
  spec.noise_sigma = 0.01;
  SparseLmCase c{makeSyntheticWindow(spec), {}, {}, {}, {}};
  const BaSettings settings = test::patchBaSettings();
  c.association = associate(c.window.scanPointers(), c.window.initial, settings.planes, 0.0);
  EXPECT_GT(c.association.problem.numPlanes(), 4u);
  c.prior = neighbourPrior(c.window.initial, {}, MotionPriorSettings{});
  c.dense = c.window.initial;
  LmSettings dense_settings;
  dense_settings.max_iterations = 50;
  dense_settings.relative_cost_tolerance = 1e-14;
  c.dense_summary = solveLevenbergMarquardt(c.association.problem, c.dense, dense_settings, c.prior);
  return c;
}

void expectSameOptimum(const SparseLmCase& c, const std::vector<Pose>& sparse, const LmSummary& s) {
  EXPECT_LT(s.final_cost, 0.05 * s.initial_cost);
  EXPECT_NEAR(s.final_cost, c.dense_summary.final_cost, 1e-6 * c.dense_summary.initial_cost);
  const auto gap = relativePoseError(sparse, c.dense);
  EXPECT_LT(gap.max_translation, 1e-4);
  EXPECT_LT(gap.max_angle_deg, 1e-3);
  EXPECT_EQ(sparse[0].t, c.window.initial[0].t);  // gauge
}

// The sparse solver reaches the same optimum as the dense one.
TEST(SparseLm, MatchesTheDenseSolver) {
  const SparseLmCase c = sparseLmCase();
  std::vector<Pose> sparse = c.window.initial;
  SparseLmSettings sparse_settings;
  sparse_settings.max_iterations = 50;
  sparse_settings.relative_cost_tolerance = 1e-14;
  sparse_settings.cg_max_iterations = 500;
  sparse_settings.cg_relative_tolerance = 1e-12;
  const LmSummary s = solveSparseLevenbergMarquardt(c.association.problem, sparse, sparse_settings, c.prior);
  expectSameOptimum(c, sparse, s);
}

// With few frames the factored system is formed and factored instead of
// iterated: exact steps reach the optimum in a few iterations even where
// one conjugate-gradient step per iteration (the setting it overrides)
// could not.
TEST(SparseLm, FormedSystemGivesExactSteps) {
  const SparseLmCase c = sparseLmCase();
  SparseLmSettings settings;
  settings.max_iterations = 8;
  settings.relative_cost_tolerance = 1e-14;
  settings.cg_max_iterations = 1;
  settings.dense_max_frames = 8;
  std::vector<Pose> formed = c.window.initial;
  const LmSummary s = solveSparseLevenbergMarquardt(c.association.problem, formed, settings, c.prior);
  expectSameOptimum(c, formed, s);

  settings.dense_max_frames = 7;  // one frame too many: conjugate gradients, one step each
  std::vector<Pose> iterated = c.window.initial;
  const LmSummary i = solveSparseLevenbergMarquardt(c.association.problem, iterated, settings, c.prior);
  EXPECT_GT(i.final_cost - c.dense_summary.final_cost, 1e-6 * c.dense_summary.initial_cost);
  std::printf("cost above the optimum: formed %.3g, iterated %.3g\n",
              s.final_cost - c.dense_summary.final_cost, i.final_cost - c.dense_summary.final_cost);
}

// The product H x sums planes in chunks fixed by the problem's size, not by
// the threads: one and two threads take identical steps on a problem large
// enough (30 000 observations) to be cut into several chunks.
TEST(SparseLm, SameStepsForAnyThreadCount) {
  std::mt19937 rng(7);
  const int frames = 40;
  const std::vector<Pose> truth = test::randomPoses(rng, frames, 5.0);
  std::vector<PlaneObservation> planes;
  for (int p = 0; p < 3000; ++p) {
    const auto first = static_cast<std::uint32_t>(p % (frames - 10));
    std::vector<std::uint32_t> seen;
    for (std::uint32_t f = first; f < first + 10; ++f) seen.push_back(f);
    planes.push_back(test::randomPlane(rng, truth, seen, 6, 0.01).observation);
  }
  const PlaneProblem problem(std::move(planes), frames);
  std::vector<Pose> start = truth;
  for (std::size_t i = 1; i < start.size(); ++i) {
    start[i] =
        Pose(so3Exp(0.002 * test::randomUnit(rng)) * start[i].R(), start[i].t + 0.02 * test::randomUnit(rng));
  }
  auto solve = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<Pose> poses = start;
    const LmSummary s = solveSparseLevenbergMarquardt(problem, poses, SparseLmSettings{});
    EXPECT_LT(s.final_cost, 0.5 * s.initial_cost);
    return poses;
  };
  const std::vector<Pose> one = solve(1);
  const std::vector<Pose> two = solve(2);
  for (int i = 0; i < frames; ++i) {
    EXPECT_EQ(one[i].t, two[i].t) << "frame " << i;
    EXPECT_EQ(one[i].q.coeffs(), two[i].q.coeffs()) << "frame " << i;
  }
}

// The preconditioner's block inverse: exact for a well-conditioned positive
// block; for an indefinite or nearly singular one, positive definite and
// bounded (the clamped diagonal it replaces turned a negative pivot into
// 1e12 and a step into 1e13 m).
TEST(SparseLm, PreconditionerBlocksArePositiveAndBounded) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix<double, 6, 6> A;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) A(r, c) = g(rng);
  }
  const Mat6 positive = A * A.transpose() + Mat6::Identity();
  EXPECT_LT((positiveInverse(positive) * positive - Mat6::Identity()).norm(), 1e-9);

  // Eigenvalues 5, 2, 1, 0.5, -0.3 and -4 (negative diagonal entries too).
  const Eigen::HouseholderQR<Mat6> qr(A);
  const Mat6 Q = qr.householderQ();
  Vec6 lambda;
  lambda << 5.0, 2.0, 1.0, 0.5, -0.3, -4.0;
  const Mat6 indefinite = Q * lambda.asDiagonal() * Q.transpose();
  const Mat6 inverse = positiveInverse(indefinite);
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(inverse);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  EXPECT_NEAR(eig.eigenvalues().maxCoeff(), 1.0 / 0.3, 1e-9);  // 1 / |smallest magnitude|
  EXPECT_LT((inverse - Q * lambda.cwiseAbs().cwiseInverse().asDiagonal() * Q.transpose()).norm(), 1e-9);

  // Nearly singular: one direction 1e-14 of the others; bounded by the floor.
  lambda << 1.0, 1.0, 1.0, 1.0, 1.0, 1e-14;
  const Mat6 singular = Q * lambda.asDiagonal() * Q.transpose();
  const Mat6 bounded = positiveInverse(singular);
  EXPECT_TRUE(bounded.allFinite());
  EXPECT_LE(Eigen::SelfAdjointEigenSolver<Mat6>(bounded).eigenvalues().maxCoeff(), 1.0001e9);
}

}  // namespace
}  // namespace hba::ba
