// Every factor kind's Ceres cost, reached through the FactorModel interface
// as the solver reaches it: the squared residual is the model's cost, and the
// tangent Jacobians match central differences. A new kind added to
// oneFactorOfEachKind is checked the same way.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include <ceres/cost_function.h>

#include "factor_model.hpp"
#include "graph_test_utils.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "hba/graph/factor_graph.hpp"
#include "hba/graph/pose_graph.hpp"
#include "orientation_held_manifold.hpp"
#include "pose_block.hpp"
#include "relative_pose_cost.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

using test::randomPose;
using test::randomVec3;
using test::randomVec6;

template <int N>
Eigen::Matrix<double, N, N> randomInformation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix<double, N, N> A;
  for (int k = 0; k < N; ++k) {
    for (int r = 0; r < N; ++r) A(r, k) = u(rng);
  }
  return A * A.transpose() + 0.1 * Eigen::Matrix<double, N, N>::Identity();
}

// Measurements far from the poses: the Jacobians must hold for large errors.
FactorGraph oneFactorOfEachKind(std::mt19937& rng) {
  FactorGraph graph;
  graph.add(RelativePoseFactor{0, 1, randomPose(rng, 5.0, 1.2), randomInformation<6>(rng)});
  graph.add(LoopClosureFactor{1, 0, randomPose(rng, 5.0, 1.2), randomInformation<6>(rng)});
  graph.add(PosePriorFactor{1, randomPose(rng, 5.0, 1.2), randomInformation<6>(rng)});
  graph.add(PositionPriorFactor{0, randomVec3(rng, 5.0), randomInformation<3>(rng)});
  graph.add(HeightPriorFactor{3, 7.5, 4.0});
  // A window of three frames whose gauge frame is not the first node.
  graph.add(WindowShapeFactor{
      {2, 0, 3}, {randomPose(rng, 5.0, 1.2), randomPose(rng, 5.0, 1.2)}, randomInformation<12>(rng)});
  return graph;
}

// Every kind, and a window long enough for the solver to take it in pieces
// (FactorModel::newCosts), its nodes out of order.
FactorGraph everyKindAndALongWindow(std::mt19937& rng) {
  FactorGraph graph = oneFactorOfEachKind(rng);
  WindowShapeFactor window{{9, 4, 5, 6, 7, 8, 13, 10, 11, 12}, {}, randomInformation<54>(rng)};
  for (int k = 0; k < 9; ++k) window.relative.push_back(randomPose(rng, 5.0, 1.2));
  graph.add(window);
  return graph;
}

std::vector<Pose> randomPoses(std::mt19937& rng, std::size_t count) {
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < count; ++k) poses.push_back(randomPose(rng));
  return poses;
}

// A Ceres cost of a factor and the pose blocks it reads.
struct PieceAt {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<PoseBlock> blocks;
};

// The factor's costs as the solver adds them: whole, or in pieces.
std::vector<PieceAt> piecesAt(const FactorModel& model, bool whole, const std::vector<Pose>& poses) {
  std::vector<PieceAt> out;
  const std::vector<std::size_t> nodes = model.nodes();
  for (CostPiece& piece : model.newCosts(whole)) {
    PieceAt at{std::move(piece.cost), {}};
    for (const std::size_t k : piece.node_positions) at.blocks.push_back(toPoseBlock(poses[nodes.at(k)]));
    out.push_back(std::move(at));
  }
  return out;
}

struct Evaluation {
  Eigen::VectorXd residual;
  std::vector<Eigen::MatrixXd> ambient_jacobians;  // one per parameter block, rows x 7
};

Evaluation evaluate(const ceres::CostFunction& cost, const std::vector<PoseBlock>& blocks) {
  Evaluation out;
  out.residual.resize(cost.num_residuals());
  std::vector<const double*> parameters;
  for (const PoseBlock& b : blocks) parameters.push_back(b.data());
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;
  std::vector<RowMajor> storage(blocks.size(), RowMajor(cost.num_residuals(), 7));
  std::vector<double*> jacobians;
  for (RowMajor& j : storage) jacobians.push_back(j.data());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), out.residual.data(), jacobians.data()));
  for (const RowMajor& j : storage) out.ambient_jacobians.emplace_back(j);
  return out;
}

Eigen::VectorXd residualAt(const ceres::CostFunction& cost, const std::vector<PoseBlock>& blocks) {
  Eigen::VectorXd residual(cost.num_residuals());
  std::vector<const double*> parameters;
  for (const PoseBlock& b : blocks) parameters.push_back(b.data());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual.data(), nullptr));
  return residual;
}

// Each block's tangent Jacobian (the ambient one times the manifold's lift,
// what LM solves with) against central differences through the manifold.
template <int N, typename Manifold>
void expectTangentJacobiansMatch(const Manifold& manifold, const ceres::CostFunction& cost,
                                 const std::vector<PoseBlock>& blocks, const std::string& what) {
  const double h = 1e-6;
  const Evaluation at = evaluate(cost, blocks);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    Eigen::Matrix<double, 7, N, Eigen::RowMajor> lift;
    manifold.PlusJacobian(blocks[b].data(), lift.data());
    const Eigen::MatrixXd tangent = at.ambient_jacobians[b] * lift;
    for (int k = 0; k < N; ++k) {
      Eigen::Matrix<double, N, 1> d = Eigen::Matrix<double, N, 1>::Zero();
      d[k] = h;
      const Eigen::Matrix<double, N, 1> minus_d = -d;
      std::vector<PoseBlock> plus = blocks;
      std::vector<PoseBlock> minus = blocks;
      manifold.Plus(blocks[b].data(), d.data(), plus[b].data());
      manifold.Plus(blocks[b].data(), minus_d.data(), minus[b].data());
      const Eigen::VectorXd numeric = (residualAt(cost, plus) - residualAt(cost, minus)) / (2 * h);
      EXPECT_LT((numeric - tangent.col(k)).norm(), 1e-6 * (1.0 + numeric.norm()))
          << what << " block " << b << " k " << k;
    }
  }
}

TEST(FactorCosts, EveryKindIsCounted) {
  std::mt19937 rng(31);
  const FactorGraph graph = oneFactorOfEachKind(rng);
  EXPECT_EQ(graph.size(), 6u);
  for (const char* kind :
       {"relative", "loop closure", "pose prior", "position prior", "height prior", "window shape"}) {
    EXPECT_EQ(graph.count(kind), 1u) << kind;
  }
}

TEST(FactorCosts, SquaredResidualIsTheFactorsCost) {
  std::mt19937 rng(32);
  for (int trial = 0; trial < 10; ++trial) {
    const FactorGraph graph = everyKindAndALongWindow(rng);
    const std::vector<Pose> poses = randomPoses(rng, 14);
    for (const auto& model : graph.models()) {
      const double expected = model->cost(poses);
      EXPECT_GT(expected, 1e-3) << model->name();  // far from the measurement
      for (const bool whole : {true, false}) {
        const std::vector<PieceAt> pieces = piecesAt(*model, whole, poses);
        if (whole) {
          EXPECT_EQ(pieces.size(), 1u);
        }
        double sum = 0.0, evaluated = 0.0;
        for (const PieceAt& piece : pieces) {
          sum += residualAt(*piece.cost, piece.blocks).squaredNorm();
          evaluated += evaluate(*piece.cost, piece.blocks).residual.squaredNorm();
        }
        EXPECT_NEAR(sum, expected, 1e-9 * expected) << model->name() << (whole ? " whole" : " in pieces");
        EXPECT_NEAR(evaluated, expected, 1e-9 * expected) << model->name();
      }
    }
  }
}

TEST(FactorCosts, ALongWindowIsSolvedInPiecesOfItsTriangularRoot) {
  std::mt19937 rng(35);
  const FactorGraph graph = everyKindAndALongWindow(rng);
  const FactorModel& window = *graph.models().back();
  const std::vector<PieceAt> pieces = piecesAt(window, false, randomPoses(rng, 14));
  // Nine frames after the first, four a piece: each piece reads the gauge
  // frame and the frames from its own on.
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].blocks.size(), 10u);
  EXPECT_EQ(pieces[1].blocks.size(), 6u);
  EXPECT_EQ(pieces[2].blocks.size(), 2u);
  EXPECT_EQ(pieces[2].cost->num_residuals(), 6);
}

TEST(FactorCosts, TangentJacobiansMatchCentralDifferences) {
  std::mt19937 rng(33);
  const WorldPoseManifold manifold;
  for (int trial = 0; trial < 10; ++trial) {
    const FactorGraph graph = everyKindAndALongWindow(rng);
    const std::vector<Pose> poses = randomPoses(rng, 14);
    for (const auto& model : graph.models()) {
      for (const bool whole : {true, false}) {
        for (const PieceAt& piece : piecesAt(*model, whole, poses))
          expectTangentJacobiansMatch<6>(manifold, *piece.cost, piece.blocks, model->name());
      }
    }
  }
}

TEST(FactorCosts, PriorResidualsAreTheDocumentedOnes) {
  std::mt19937 rng(34);
  const Pose pose = randomPose(rng);
  const Pose measured = randomPose(rng, 5.0, 1.0);
  const Vec3 position = randomVec3(rng, 5.0);
  FactorGraph graph;
  graph.add(PosePriorFactor{0, measured, Mat6::Identity()});
  graph.add(PositionPriorFactor{0, position, Mat3::Identity()});
  const std::vector<PoseBlock> blocks = {toPoseBlock(pose)};

  // The pose prior is a relative factor from the world origin ...
  const std::unique_ptr<ceres::CostFunction> pose_prior(graph.models()[0]->newCost());
  const Eigen::VectorXd e = residualAt(*pose_prior, blocks);
  EXPECT_LT((e - relativePoseError(measured, Pose(), pose)).norm(), 1e-12);
  EXPECT_LT((e.head<3>() - measured.R().transpose() * (pose.t - measured.t)).norm(), 1e-9);
  EXPECT_LT((e.tail<3>() - so3Log(Quat(measured.q.conjugate() * pose.q))).norm(), 1e-9);
  // ... which vanishes at the measurement,
  EXPECT_LT(residualAt(*pose_prior, {toPoseBlock(measured)}).norm(), 1e-12);
  // and the position prior is the world offset of the position.
  const std::unique_ptr<ceres::CostFunction> position_prior(graph.models()[1]->newCost());
  EXPECT_LT((residualAt(*position_prior, blocks) - (pose.t - position)).norm(), 1e-12);
}

// Two nodes 1 m apart along x, the first held near the origin by a position
// prior: a height prior of 0.3 m on the second, as stiff as the relative
// factor, meets it where the three quadratic costs balance (z 0.1 and 0.2).
TEST(FactorCosts, HeightPriorPullsByItsWeight) {
  FactorGraph graph;
  graph.add(PositionPriorFactor{0, Vec3::Zero(), Mat3::Identity()});
  graph.add(RelativePoseFactor{0, 1, Pose(Quat::Identity(), Vec3(1, 0, 0)), Mat6::Identity()});
  graph.add(HeightPriorFactor{1, 0.3, 1.0});
  const std::vector<Pose> start = {Pose(), Pose(Quat::Identity(), Vec3(1, 0, 0))};
  const PoseGraphResult solved = optimizeFactorGraph(start, graph, PoseGraphSettings{});
  EXPECT_NEAR(solved.poses[0].t.z(), 0.1, 1e-6);
  EXPECT_NEAR(solved.poses[1].t.z(), 0.2, 1e-6);
  EXPECT_NEAR(solved.poses[1].t.x(), 1.0, 1e-6);
  FactorGraph bad;
  bad.add(HeightPriorFactor{0, std::nan(""), 1.0});
  EXPECT_THROW(optimizeFactorGraph(start, bad, PoseGraphSettings{}), Error);
}

TEST(OrientationHeldManifold, MovesThePositionOnlyAndInvertsItself) {
  std::mt19937 rng(35);
  const OrientationHeldManifold manifold;
  const PoseBlock x = toPoseBlock(randomPose(rng));
  const Vec3 delta = randomVec3(rng, 2.0);
  PoseBlock moved{};
  ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), moved.data()));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(moved[k], x[k] + delta[k]);
  for (int k = 3; k < 7; ++k) EXPECT_EQ(moved[k], x[k]);  // the rotation, bit for bit
  Vec3 back;
  ASSERT_TRUE(manifold.Minus(moved.data(), x.data(), back.data()));
  EXPECT_LT((back - delta).norm(), 1e-12);

  Eigen::Matrix<double, 7, 3, Eigen::RowMajor> plus_jacobian;
  Eigen::Matrix<double, 3, 7, Eigen::RowMajor> minus_jacobian;
  ASSERT_TRUE(manifold.PlusJacobian(x.data(), plus_jacobian.data()));
  ASSERT_TRUE(manifold.MinusJacobian(x.data(), minus_jacobian.data()));
  EXPECT_LT((minus_jacobian * plus_jacobian - Mat3::Identity()).norm(), 1e-15);
}

TEST(OrientationHeldManifold, GivesTheSolverTheTranslationColumnsOfTheTangentJacobian) {
  std::mt19937 rng(36);
  const RelativePoseCost cost(randomPose(rng, 3.0, 1.0), Mat6::Identity());
  const std::vector<PoseBlock> blocks = {toPoseBlock(randomPose(rng)), toPoseBlock(randomPose(rng))};
  expectTangentJacobiansMatch<3>(OrientationHeldManifold(), cost, blocks, "orientation held");
}

}  // namespace
}  // namespace hba::graph
