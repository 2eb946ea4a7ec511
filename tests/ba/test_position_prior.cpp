// Position priors in the refinement's plane BA: their derivative, the best
// rigid move of a whole sequence onto them, and a sparse LM that, with no
// frame held, puts the frames where the priors and planes say.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "hba/ba/lm_solver.hpp"
#include "hba/ba/position_prior.hpp"
#include "hba/ba/sparse_lm.hpp"
#include "hba/core/lie.hpp"
#include "random_planes.hpp"

namespace hba::ba {
namespace {

Mat3 randomInformation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.5, 4.0);
  const Mat3 R = so3Exp(test::randomUnit(rng));
  return R * Vec3(u(rng), u(rng), u(rng)).asDiagonal() * R.transpose();
}

TEST(PositionPrior, JacobianMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  const Pose pose = test::randomPoses(rng, 1, 20.0).front();
  PositionTerm term;
  term.offset = Vec3(1.5, -0.7, 2.0);
  term.position = Vec3(3.0, 1.0, -2.0);
  term.weight = randomInformation(rng);
  const Eigen::Matrix<double, 3, 6> J = PositionPriors::jacobian(term, pose);
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(6);
    d(k) = h;
    const Vec3 plus = PositionPriors::error(term, applyUpdate({pose}, d).front());
    const Vec3 minus = PositionPriors::error(term, applyUpdate({pose}, -d).front());
    const Vec3 numeric = (plus - minus) / (2.0 * h);
    EXPECT_LT((numeric - J.col(k)).norm(), 1e-7) << "column " << k;
  }
}

// Frames at `truth`, priors on every third (some with an offset point).
PositionPriors priorsFrom(const std::vector<Pose>& truth, std::mt19937& rng) {
  std::vector<PositionTerm> terms;
  for (std::size_t i = 0; i < truth.size(); i += 3) {
    PositionTerm term;
    term.frame = i;
    term.offset = i % 2 == 0 ? Vec3::Zero() : Vec3(0.3, -1.0, 0.5);
    term.position = truth[i] * term.offset;
    term.weight = randomInformation(rng);
    terms.push_back(term);
  }
  return PositionPriors(std::move(terms));
}

TEST(PositionPrior, BestRigidMoveRecoversAKnownMove) {
  std::mt19937 rng(5);
  const std::vector<Pose> truth = test::randomPoses(rng, 30, 50.0);
  const PositionPriors priors = priorsFrom(truth, rng);
  // The sequence turned by 20 degrees and shifted far (UTM-like).
  const Pose moved_by(so3Exp(Vec3(0.05, -0.1, 0.35)), Vec3(3000.0, -1200.0, 40.0));
  std::vector<Pose> poses = truth;
  for (Pose& pose : poses) pose = moved_by * pose;
  EXPECT_GT(priors.cost(poses), 1.0);
  const Pose move = priors.bestRigidMove(poses);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose back = move * poses[i];
    EXPECT_LT((back.t - truth[i].t).norm(), 1e-6) << "frame " << i;
    EXPECT_LT((back.R() - truth[i].R()).norm(), 1e-8) << "frame " << i;
  }
  std::vector<Pose> moved = poses;
  for (Pose& pose : moved) pose = move * pose;
  EXPECT_LT(priors.cost(moved), 1e-10);
}

// Priors along a line cannot say how the sequence is turned about it: the
// move is then finite and leaves that turn alone.
TEST(PositionPrior, PriorsAlongALineGiveAFiniteMove) {
  std::vector<Pose> poses;
  std::vector<PositionTerm> terms;
  for (int i = 0; i < 10; ++i) {
    poses.emplace_back(Mat3::Identity(), Vec3(5.0 * i, 0.0, 0.0));
    PositionTerm term;
    term.frame = static_cast<std::size_t>(i);
    term.position = Vec3(5.0 * i + 2.0, 1.0, 0.0);
    term.weight = Mat3::Identity();
    terms.push_back(term);
  }
  const PositionPriors priors(std::move(terms));
  EXPECT_FALSE(priors.defineTheFrame(10.0));
  const Pose move = priors.bestRigidMove(poses);
  ASSERT_TRUE(move.t.allFinite());
  for (const Pose& pose : poses) {
    EXPECT_LT(((move * pose).t - pose.t - Vec3(2.0, 1.0, 0.0)).norm(), 1e-6);
  }
  EXPECT_LT(so3Log(move.R()).norm(), 1e-6);
}

TEST(PositionPrior, SpreadDecidesWhetherPriorsDefineTheFrame) {
  std::vector<PositionTerm> terms(3);
  terms[0].position = Vec3(0.0, 0.0, 0.0);
  terms[1].position = Vec3(100.0, 0.0, 0.0);
  EXPECT_FALSE(PositionPriors({terms[0], terms[1]}).defineTheFrame(10.0));  // two points
  terms[2].position = Vec3(50.0, 5.0, 0.0);
  EXPECT_FALSE(PositionPriors(terms).defineTheFrame(10.0));  // nearly a line
  terms[2].position = Vec3(50.0, 60.0, 0.0);
  EXPECT_TRUE(PositionPriors(terms).defineTheFrame(10.0));
}

// A sequence whose planes agree but which sits turned and shifted away
// from its priors: with no frame held the sparse LM brings every frame
// back onto the truth (the rigid part exactly, the rest by the planes);
// holding frame 0, as without priors, it cannot.
TEST(PositionPrior, SparseLmWithPriorsNeedsNoHeldFrame) {
  std::mt19937 rng(11);
  const int frames = 40;
  const std::vector<Pose> truth = test::randomPoses(rng, frames, 20.0);
  std::vector<PlaneObservation> planes;
  for (int p = 0; p < 600; ++p) {
    const auto first = static_cast<std::uint32_t>(p % (frames - 6));
    std::vector<std::uint32_t> seen;
    for (std::uint32_t f = first; f < first + 6; ++f) seen.push_back(f);
    planes.push_back(test::randomPlane(rng, truth, seen, 8, 0.002).observation);
  }
  const PlaneProblem problem(std::move(planes), frames);
  std::vector<PositionTerm> terms = priorsFrom(truth, rng).terms();
  for (PositionTerm& term : terms) term.weight *= 1e-4;  // weak next to the planes
  const PositionPriors priors(std::move(terms));

  const Pose away(so3Exp(Vec3(0.0, 0.0, 0.03)), Vec3(2.0, -1.0, 0.5));
  std::vector<Pose> start = truth;
  for (std::size_t i = 0; i < start.size(); ++i) {
    start[i] = away * Pose(so3Exp(0.003 * test::randomUnit(rng)) * truth[i].R(),
                           truth[i].t + 0.03 * test::randomUnit(rng));
  }
  SparseLmSettings settings;
  settings.max_iterations = 30;
  settings.hold_first = false;
  std::vector<Pose> free = start;
  solveSparseLevenbergMarquardt(problem, free, settings, {}, priors);
  double worst = 0.0;
  for (int i = 0; i < frames; ++i) worst = std::max(worst, (free[i].t - truth[i].t).norm());
  std::printf("largest distance from the truth: %.4f m with no frame held\n", worst);
  // The planes of this random chain leave its shape centimetres loose (its
  // plane cost is below the truth's there): the priors fix the rest.
  EXPECT_LT(worst, 0.05);

  settings.hold_first = true;
  std::vector<Pose> held = start;
  solveSparseLevenbergMarquardt(problem, held, settings, {}, priors);
  EXPECT_EQ(held[0].t, start[0].t);
  double worst_held = 0.0;
  for (int i = 0; i < frames; ++i) worst_held = std::max(worst_held, (held[i].t - truth[i].t).norm());
  std::printf("largest distance from the truth: %.4f m with frame 0 held\n", worst_held);
  EXPECT_GT(worst_held, 0.5);
}

}  // namespace
}  // namespace hba::ba
