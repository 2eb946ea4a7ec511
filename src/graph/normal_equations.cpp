#include "normal_equations.hpp"

#include <algorithm>
#include <cstring>

#include <ceres/cost_function.h>
#include <cholmod.h>

#include "hba/core/error.hpp"
#include "pose_block.hpp"
#include "world_pose_manifold.hpp"

namespace hba::graph {
namespace {

using AmbientJacobian = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;
using TangentJacobian = Eigen::Matrix<double, Eigen::Dynamic, 6>;
using PlusJacobian = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;

}  // namespace

// Up to this many unknowns (500 poses) the factorization is simplicial.
constexpr std::size_t kSupernodalUnknowns = 3000;

// CHOLMOD's workspace, the damped matrix (the pattern filled once) and its
// symbolic factorization, found at the first solve and kept.
struct NormalEquations::Cholmod {
  cholmod_common common{};
  cholmod_sparse* matrix = nullptr;
  cholmod_factor* factor = nullptr;

  Cholmod() {
    cholmod_start(&common);
    common.print = 0;
  }
  ~Cholmod() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    if (matrix != nullptr) cholmod_free_sparse(&matrix, &common);
    cholmod_finish(&common);
  }
};

NormalEquations::NormalEquations(const std::vector<bool>& variable,
                                 const std::vector<std::vector<std::size_t>>& factor_nodes)
    : index_(variable.size(), -1), cholmod_(std::make_unique<Cholmod>()) {
  long unknowns = 0;
  for (std::size_t node = 0; node < variable.size(); ++node)
    if (variable[node]) index_[node] = unknowns++;
  above_.resize(static_cast<std::size_t>(unknowns));
  for (const std::vector<std::size_t>& nodes : factor_nodes) {
    for (const std::size_t a : nodes) {
      for (const std::size_t b : nodes) {
        if (index_[a] >= 0 && index_[b] >= 0 && index_[a] < index_[b])
          above_[static_cast<std::size_t>(index_[b])].push_back(static_cast<std::size_t>(index_[a]));
      }
    }
  }
  column_start_.assign(6 * above_.size() + 1, 0);
  for (std::size_t j = 0; j < above_.size(); ++j) {
    std::vector<std::size_t>& rows = above_[j];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (std::size_t c = 0; c < 6; ++c)
      column_start_[6 * j + c + 1] = column_start_[6 * j + c] + 6 * rows.size() + c + 1;
  }
  hessian_.assign(column_start_.back(), 0.0);
  gradient_.assign(6 * above_.size(), 0.0);

  // The pattern for CHOLMOD: the upper triangle (stype 1), rows sorted.
  const std::size_t n = gradient_.size();
  Cholmod& cm = *cholmod_;
  cm.matrix = cholmod_allocate_sparse(n, n, hessian_.size(), 1, 1, 1, CHOLMOD_REAL, &cm.common);
  if (cm.matrix == nullptr) throw Error("pose graph: CHOLMOD could not allocate the normal equations");
  auto* starts = static_cast<int*>(cm.matrix->p);
  auto* rows = static_cast<int*>(cm.matrix->i);
  for (std::size_t j = 0; j < above_.size(); ++j) {
    for (std::size_t c = 0; c < 6; ++c) {
      const std::size_t column = 6 * j + c;
      starts[column] = static_cast<int>(column_start_[column]);
      std::size_t k = column_start_[column];
      for (const std::size_t i : above_[j])
        for (std::size_t r = 0; r < 6; ++r) rows[k++] = static_cast<int>(6 * i + r);
      for (std::size_t r = 0; r <= c; ++r) rows[k++] = static_cast<int>(6 * j + r);
    }
  }
  starts[n] = static_cast<int>(hessian_.size());
}

NormalEquations::~NormalEquations() = default;

void NormalEquations::clear() {
  std::fill(hessian_.begin(), hessian_.end(), 0.0);
  std::fill(gradient_.begin(), gradient_.end(), 0.0);
  cost_ = 0.0;
}

double& NormalEquations::entry(std::size_t column_block, std::size_t row_block, int row, int column) {
  const std::vector<std::size_t>& rows = above_[column_block];
  const std::size_t start = column_start_[6 * column_block + static_cast<std::size_t>(column)];
  if (row_block == column_block) return hessian_[start + 6 * rows.size() + static_cast<std::size_t>(row)];
  const auto at = std::lower_bound(rows.begin(), rows.end(), row_block);
  return hessian_[start + 6 * static_cast<std::size_t>(at - rows.begin()) + static_cast<std::size_t>(row)];
}

void NormalEquations::addGradient(std::size_t node, const Vec6& gradient) {
  const long k = index_[node];
  if (k < 0) return;
  for (int r = 0; r < 6; ++r) gradient_[static_cast<std::size_t>(6 * k + r)] += gradient[r];
}

void NormalEquations::addHessian(std::size_t a, std::size_t b, const Mat6& block) {
  const long ia = index_[a];
  const long ib = index_[b];
  if (ia < 0 || ib < 0) return;
  const auto column_block = static_cast<std::size_t>(std::max(ia, ib));
  const auto row_block = static_cast<std::size_t>(std::min(ia, ib));
  for (int c = 0; c < 6; ++c) {
    if (ia == ib) {
      for (int r = 0; r <= c; ++r) entry(column_block, row_block, r, c) += block(r, c);
    } else {
      // Stored: rows of the lower-numbered node, columns of the other.
      double* column = &entry(column_block, row_block, 0, c);
      for (int r = 0; r < 6; ++r) column[r] += ia < ib ? block(r, c) : block(c, r);
    }
  }
}

bool NormalEquations::factorDamped(double lambda) {
  Cholmod& cm = *cholmod_;
  factored_ = false;
  auto* values = static_cast<double*>(cm.matrix->x);
  std::memcpy(values, hessian_.data(), hessian_.size() * sizeof(double));
  for (std::size_t k = 0; k < gradient_.size(); ++k) {
    const std::size_t diagonal = column_start_[k + 1] - 1;  // a column's last entry
    values[diagonal] += lambda * std::clamp(hessian_[diagonal], 1e-6, 1e32);
  }
  if (cm.factor == nullptr) {
    // Small systems factored without BLAS (simplicial): cheap at their size,
    // and the same bits in every process. The supernodal factorization's
    // BLAS calls end a few last bits apart between processes (the CLI and
    // the Python module), as Ceres' did on the same graphs.
    if (gradient_.size() < kSupernodalUnknowns) cm.common.supernodal = CHOLMOD_SIMPLICIAL;
    cm.factor = cholmod_analyze(cm.matrix, &cm.common);
  }
  if (cm.factor == nullptr) throw Error("pose graph: CHOLMOD could not order the normal equations");
  factored_ = cholmod_factorize(cm.matrix, cm.factor, &cm.common) && cm.common.status == CHOLMOD_OK;
  return factored_;
}

bool NormalEquations::solve(std::vector<Vec6>& delta) const {
  if (!factored_) return false;
  Cholmod& cm = *cholmod_;
  const std::size_t n = gradient_.size();
  cholmod_dense* rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &cm.common);
  if (rhs == nullptr) throw Error("pose graph: CHOLMOD could not allocate a vector");
  auto* b = static_cast<double*>(rhs->x);
  for (std::size_t k = 0; k < n; ++k) b[k] = -gradient_[k];
  cholmod_dense* solution = cholmod_solve(CHOLMOD_A, cm.factor, rhs, &cm.common);
  cholmod_free_dense(&rhs, &cm.common);
  if (solution == nullptr) return false;
  const auto* x = static_cast<const double*>(solution->x);
  delta.assign(index_.size(), Vec6::Zero());
  for (std::size_t node = 0; node < index_.size(); ++node) {
    if (index_[node] < 0) continue;
    for (int r = 0; r < 6; ++r) delta[node][r] = x[6 * index_[node] + r];
  }
  cholmod_free_dense(&solution, &cm.common);
  return std::all_of(delta.begin(), delta.end(), [](const Vec6& d) { return d.allFinite(); });
}

// A factor's terms from its Ceres cost (whitened residual r = S e, so
// r^T r = e^T Omega e): its Jacobian in the nodes' tangent, the product of
// the cost's and the manifold's.
void addTermsFromCost(const ceres::CostFunction& cost, const std::vector<std::size_t>& nodes,
                      const std::vector<Pose>& poses, NormalEquations& system) {
  const auto m = static_cast<Eigen::Index>(cost.num_residuals());
  std::vector<PoseBlock> blocks(nodes.size());
  std::vector<const double*> parameters(nodes.size());
  std::vector<AmbientJacobian> ambient(nodes.size(), AmbientJacobian(m, 7));
  std::vector<double*> jacobians(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    blocks[k] = toPoseBlock(poses[nodes[k]]);
    parameters[k] = blocks[k].data();
    jacobians[k] = system.isVariable(nodes[k]) ? ambient[k].data() : nullptr;
  }
  Eigen::VectorXd residual(m);
  cost.Evaluate(parameters.data(), residual.data(), jacobians.data());
  system.addCost(residual.squaredNorm());

  const WorldPoseManifold manifold;
  std::vector<TangentJacobian> tangent(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (jacobians[k] == nullptr) continue;
    PlusJacobian plus;
    manifold.PlusJacobian(blocks[k].data(), plus.data());
    tangent[k] = ambient[k] * plus;
    system.addGradient(nodes[k], tangent[k].transpose() * residual);
  }
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    if (jacobians[a] == nullptr) continue;
    for (std::size_t b = a; b < nodes.size(); ++b) {
      if (jacobians[b] != nullptr) system.addHessian(nodes[a], nodes[b], tangent[a].transpose() * tangent[b]);
    }
  }
}

Eigen::MatrixXd NormalEquations::hessian() const {
  const auto n = static_cast<Eigen::Index>(gradient_.size());
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  const auto* rows = static_cast<const int*>(cholmod_->matrix->i);
  for (Eigen::Index column = 0; column < n; ++column) {
    for (std::size_t k = column_start_[static_cast<std::size_t>(column)];
         k < column_start_[static_cast<std::size_t>(column) + 1]; ++k) {
      dense(rows[k], column) = dense(column, rows[k]) = hessian_[k];
    }
  }
  return dense;
}

Eigen::VectorXd NormalEquations::gradient() const {
  return Eigen::Map<const Eigen::VectorXd>(gradient_.data(), static_cast<Eigen::Index>(gradient_.size()));
}

double NormalEquations::predictedDecrease(const std::vector<Vec6>& delta) const {
  Eigen::VectorXd d(static_cast<Eigen::Index>(gradient_.size()));
  for (std::size_t node = 0; node < index_.size(); ++node)
    if (index_[node] >= 0) d.segment<6>(6 * index_[node]) = delta[node];
  const Eigen::Map<const Eigen::VectorXd> g(gradient_.data(), d.size());
  // H d from the upper triangle, column by column.
  Eigen::VectorXd hd = Eigen::VectorXd::Zero(d.size());
  auto* rows = static_cast<const int*>(cholmod_->matrix->i);
  for (Eigen::Index column = 0; column < d.size(); ++column) {
    for (std::size_t k = column_start_[static_cast<std::size_t>(column)];
         k < column_start_[static_cast<std::size_t>(column) + 1]; ++k) {
      const Eigen::Index row = rows[k];
      hd[row] += hessian_[k] * d[column];
      if (row != column) hd[column] += hessian_[k] * d[row];
    }
  }
  return -(2.0 * g.dot(d) + d.dot(hd));
}

}  // namespace hba::graph
