// Window-shape factors: a whole BA window's relative poses from its first
// frame, with their joint information (see WindowShapeFactor).
#include <algorithm>
#include <memory>
#include <string>

#include <ceres/cost_function.h>
#include <Eigen/Cholesky>

#include "factor_model.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "information_root.hpp"
#include "normal_equations.hpp"
#include "pose_block.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

using RowMajorJacobian = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;

// S with S^T S = information: L^T of a Cholesky factor where it is positive
// definite (the clamped information always is), the eigen-decomposition's
// root otherwise. Cholesky is an order of magnitude cheaper for the
// hundreds of rows of a large window, and its S is upper triangular.
struct SquareRoot {
  Eigen::MatrixXd s;
  bool upper_triangular = false;
};

SquareRoot squareRoot(const Eigen::MatrixXd& information, const std::string& what) {
  const Eigen::LLT<Eigen::MatrixXd> cholesky(0.5 * (information + information.transpose()));
  if (cholesky.info() == Eigen::Success && information.allFinite()) return {cholesky.matrixU(), true};
  return {informationRoot<Eigen::Dynamic>(information, what), false};
}

// Rows of the residual S * [e_1; ...; e_{K-1}], e_k the relative-pose error
// of frame k from frame 0, that depend on the frames from some frame f on
// only: `relative` holds the measurements of frames f..K-1 and `rows` those
// rows of S, their columns those frames'. Parameter blocks: frame 0, then
// frames f..K-1 in node order. f = 1 and every row: the whole factor.
class WindowShapeCost final : public ceres::CostFunction {
 public:
  WindowShapeCost(std::vector<Pose> relative, Eigen::MatrixXd rows)
      : relative_(std::move(relative)), rows_(std::move(rows)) {
    set_num_residuals(static_cast<int>(rows_.rows()));
    for (std::size_t k = 0; k <= relative_.size(); ++k) mutable_parameter_block_sizes()->push_back(7);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Index m = rows_.rows();
    const Eigen::Index n = rows_.cols();
    const Pose first = poseFromBlock(parameters[0]);
    Eigen::VectorXd error(n);
    Eigen::MatrixXd d_first;  // d error / d first's tangent, n x 6
    const bool want_first = jacobians && jacobians[0];
    if (want_first) d_first.setZero(n, 6);
    for (std::size_t k = 1; k <= relative_.size(); ++k) {
      const Eigen::Index col = static_cast<Eigen::Index>(6 * (k - 1));
      const Pose frame = poseFromBlock(parameters[k]);
      if (!jacobians) {
        error.segment<6>(col) = relativePoseError(relative_[k - 1], first, frame);
        continue;
      }
      const RelativePoseErrorJacobians e = relativePoseErrorJacobians(relative_[k - 1], first, frame);
      error.segment<6>(col) = e.error;
      if (want_first) d_first.middleRows<6>(col) = e.d_from;
      if (jacobians[k]) {
        // Only frame k's own six errors depend on it.
        Eigen::Map<RowMajorJacobian> d_frame(jacobians[k], m, 7);
        d_frame.noalias() = rows_.middleCols<6>(col) * e.d_to * tangentToAmbient(frame.q);
      }
    }
    Eigen::Map<Eigen::VectorXd>(residuals, m).noalias() = rows_ * error;
    if (want_first) {
      Eigen::Map<RowMajorJacobian> d_gauge(jacobians[0], m, 7);
      d_gauge.noalias() = rows_ * d_first * tangentToAmbient(first.q);
    }
    return true;
  }

 private:
  std::vector<Pose> relative_;
  Eigen::MatrixXd rows_;
};

// Rows of an upper-triangular S per piece: each piece's rows depend on the
// frames from its first row's frame on, so Ceres' J^T J of a window of K
// frames costs about a third of the whole factor's, while each piece
// computes the errors of the frames it sees again.
constexpr std::size_t kFramesPerPiece = 4;

class WindowShapeFactorModel final : public FactorModel {
 public:
  explicit WindowShapeFactorModel(const WindowShapeFactor& f) : factor_(f) {}
  const char* name() const override { return "window shape"; }
  std::vector<std::size_t> nodes() const override { return factor_.nodes; }
  LossGroup lossGroup() const override { return LossGroup::Window; }

  void validate(std::size_t num_poses, const std::string& label) const override {
    const std::size_t k = factor_.nodes.size();
    if (k < 2) throw Error(label + " needs at least two nodes");
    if (factor_.relative.size() + 1 != k) {
      throw Error(label + " has " + std::to_string(factor_.relative.size()) + " measurements for " +
                  std::to_string(k) + " nodes (one fewer expected)");
    }
    const auto size = static_cast<Eigen::Index>(6 * (k - 1));
    if (factor_.information.rows() != size || factor_.information.cols() != size) {
      throw Error(label + ": information is " + std::to_string(factor_.information.rows()) + "x" +
                  std::to_string(factor_.information.cols()) + ", expected " + std::to_string(size) + "x" +
                  std::to_string(size));
    }
    std::vector<std::size_t> sorted = factor_.nodes;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      throw Error(label + " links a node to itself");
    }
    for (const std::size_t node : factor_.nodes) checkNode(node, num_poses, label);
    for (const Pose& measurement : factor_.relative) checkFinite(measurement, label);
    squareRoot(factor_.information, label + ": information");
  }

  double cost(const std::vector<Pose>& poses) const override {
    Eigen::VectorXd error(factor_.information.rows());
    for (std::size_t k = 1; k < factor_.nodes.size(); ++k) {
      error.segment<6>(static_cast<Eigen::Index>(6 * (k - 1))) =
          relativePoseError(factor_.relative[k - 1], poses[factor_.nodes[0]], poses[factor_.nodes[k]]);
    }
    return error.dot(factor_.information * error);
  }

  ceres::CostFunction* newCost() const override {
    return new WindowShapeCost(factor_.relative,
                               squareRoot(factor_.information, "window shape information").s);
  }

  bool formsNormalEquations() const override { return true; }

  // Each error e_k depends on the first frame (D0_k) and frame k (Dk) only:
  // J^T Omega J block by block, about K^2 products of 6x6 blocks, where
  // J^T J of the whitened rows costs about K^3.
  void addNormalEquations(const std::vector<Pose>& poses, NormalEquations& system) const override {
    const std::vector<std::size_t>& nodes = factor_.nodes;
    const std::size_t frames = factor_.relative.size();
    const Eigen::MatrixXd& omega = factor_.information;
    Eigen::VectorXd error(omega.rows());
    std::vector<Mat6> d_first(frames);
    std::vector<Mat6> d_own(frames);
    for (std::size_t k = 0; k < frames; ++k) {
      const RelativePoseErrorJacobians e =
          relativePoseErrorJacobians(factor_.relative[k], poses[nodes[0]], poses[nodes[k + 1]]);
      error.segment<6>(static_cast<Eigen::Index>(6 * k)) = e.error;
      d_first[k] = e.d_from;
      d_own[k] = e.d_to;
    }
    const Eigen::VectorXd weighted = omega * error;
    system.addCost(error.dot(weighted));
    // Omega times the Jacobian's columns: of each frame, and of the first.
    Eigen::MatrixXd omega_own(omega.rows(), omega.cols());
    Eigen::Matrix<double, Eigen::Dynamic, 6> omega_first =
        Eigen::Matrix<double, Eigen::Dynamic, 6>::Zero(omega.rows(), 6);
    Vec6 first_gradient = Vec6::Zero();
    for (std::size_t l = 0; l < frames; ++l) {
      const auto col = static_cast<Eigen::Index>(6 * l);
      omega_own.middleCols<6>(col).noalias() = omega.middleCols<6>(col) * d_own[l];
      omega_first.noalias() += omega.middleCols<6>(col) * d_first[l];
      system.addGradient(nodes[l + 1], d_own[l].transpose() * weighted.segment<6>(col));
      first_gradient.noalias() += d_first[l].transpose() * weighted.segment<6>(col);
    }
    system.addGradient(nodes[0], first_gradient);
    Mat6 first_first = Mat6::Zero();
    for (std::size_t l = 0; l < frames; ++l) {
      const auto col = static_cast<Eigen::Index>(6 * l);
      Mat6 first_own = Mat6::Zero();
      for (std::size_t k = 0; k < frames; ++k) {
        const auto row = static_cast<Eigen::Index>(6 * k);
        if (k <= l)
          system.addHessian(nodes[k + 1], nodes[l + 1],
                            d_own[k].transpose() * omega_own.block<6, 6>(row, col));
        first_own.noalias() += d_first[k].transpose() * omega_own.block<6, 6>(row, col);
      }
      system.addHessian(nodes[0], nodes[l + 1], first_own);
      first_first.noalias() += d_first[l].transpose() * omega_first.middleRows<6>(col);
    }
    system.addHessian(nodes[0], nodes[0], first_first);
  }

  std::vector<CostPiece> newCosts(bool whole) const override {
    const std::size_t frames = factor_.relative.size();  // after the first
    if (whole || frames <= kFramesPerPiece) return FactorModel::newCosts(true);
    const SquareRoot root = squareRoot(factor_.information, "window shape information");
    if (!root.upper_triangular) return FactorModel::newCosts(true);
    std::vector<CostPiece> pieces;
    for (std::size_t from = 0; from < frames; from += kFramesPerPiece) {
      const auto row = static_cast<Eigen::Index>(6 * from);
      const auto rows = static_cast<Eigen::Index>(6 * std::min(kFramesPerPiece, frames - from));
      const std::vector<Pose> seen(factor_.relative.begin() + static_cast<long>(from),
                                   factor_.relative.end());
      CostPiece piece{
          std::make_unique<WindowShapeCost>(seen, root.s.block(row, row, rows, root.s.cols() - row)), {0}};
      for (std::size_t k = from + 1; k <= frames; ++k) piece.node_positions.push_back(k);
      pieces.push_back(std::move(piece));
    }
    return pieces;
  }

 private:
  WindowShapeFactor factor_;
};

}  // namespace

FactorModelPtr modelOf(const WindowShapeFactor& factor) {
  return std::make_shared<const WindowShapeFactorModel>(factor);
}

}  // namespace hba::graph
