#pragma once
// The pose graph's Gauss-Newton system in the poses' tangent (dt, dphi):
// H = J^T Omega J and g = J^T Omega e summed over the factors, kept as the
// upper triangle of a block-sparse matrix whose pattern the factors' nodes
// fix once, and factored by CHOLMOD. Ceres forms J^T J from a window-shape
// factor's dense rows; a factor that knows its Jacobian's structure adds
// its blocks here directly (FactorModel::addNormalEquations).
#include <cstddef>
#include <memory>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace ceres {
class CostFunction;
}

namespace hba::graph {

class NormalEquations {
 public:
  // The unknowns: the nodes with `variable[node]`, six each in node order;
  // blocks between every two of them some factor links (`factor_nodes`).
  NormalEquations(const std::vector<bool>& variable,
                  const std::vector<std::vector<std::size_t>>& factor_nodes);
  ~NormalEquations();
  NormalEquations(const NormalEquations&) = delete;
  NormalEquations& operator=(const NormalEquations&) = delete;

  bool isVariable(std::size_t node) const { return index_[node] >= 0; }
  // Zero cost, gradient and Hessian, pattern kept.
  void clear();
  void addCost(double cost) { cost_ += cost; }
  // d(cost)/2 by the node's tangent; ignored for a node that is not variable.
  void addGradient(std::size_t node, const Vec6& gradient);
  // The Hessian/2 block of rows `a`, columns `b` (each unordered pair of
  // distinct nodes once; a == b its diagonal block); ignored unless both
  // are variable.
  void addHessian(std::size_t a, std::size_t b, const Mat6& block);

  double cost() const { return cost_; }
  // Factors H + lambda diag(H), the diagonal clamped to [1e-6, 1e32] as
  // Ceres' Levenberg-Marquardt does; false where it is not positive
  // definite. The factor is kept until the next call.
  bool factorDamped(double lambda);
  // delta = -(the last factored matrix)^-1 g, g as it is now (the factor
  // may be of an earlier linearization); false without a factor. `delta`
  // holds six numbers a node, zero for the nodes that are not variable.
  bool solve(std::vector<Vec6>& delta) const;
  // -(2 g^T delta + delta^T H delta): the decrease the quadratic model
  // predicts for the step.
  double predictedDecrease(const std::vector<Vec6>& delta) const;
  // H (both triangles) and g over the unknowns, for tests.
  Eigen::MatrixXd hessian() const;
  Eigen::VectorXd gradient() const;

 private:
  struct Cholmod;
  double& entry(std::size_t column_block, std::size_t row_block, int row, int column);

  std::vector<long> index_;                      // node -> unknown block, or -1
  std::vector<std::vector<std::size_t>> above_;  // per block column: block rows above the diagonal, sorted
  std::vector<std::size_t> column_start_;        // per scalar column: its first value
  std::vector<double> hessian_;                  // the upper triangle, column by column
  std::vector<double> gradient_;
  double cost_ = 0.0;
  bool factored_ = false;
  std::unique_ptr<Cholmod> cholmod_;
};

// A factor's terms from its Ceres cost over `nodes` (whitened residual
// r = S e, so r^T r = e^T Omega e): its Jacobian in the nodes' tangent is
// the cost's times the manifold's PlusJacobian.
void addTermsFromCost(const ceres::CostFunction& cost, const std::vector<std::size_t>& nodes,
                      const std::vector<Pose>& poses, NormalEquations& system);

}  // namespace hba::graph
