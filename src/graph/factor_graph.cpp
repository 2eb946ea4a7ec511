#include "hba/graph/factor_graph.hpp"

#include <numeric>
#include <string>

#include "factor_model.hpp"
#include "hba/core/error.hpp"

namespace hba::graph {

FactorGraph::FactorGraph(const std::vector<RelativePoseFactor>& relative_factors) {
  models_.reserve(relative_factors.size());
  for (const RelativePoseFactor& factor : relative_factors) add(factor);
}

std::size_t FactorGraph::count(std::string_view kind) const {
  std::size_t n = 0;
  for (const auto& model : models_) n += model->name() == kind ? 1 : 0;
  return n;
}

std::vector<CostPiece> FactorModel::newCosts(bool /*whole*/) const {
  std::vector<CostPiece> pieces(1);
  pieces[0].cost.reset(newCost());
  pieces[0].node_positions.resize(nodes().size());
  std::iota(pieces[0].node_positions.begin(), pieces[0].node_positions.end(), std::size_t{0});
  return pieces;
}

void FactorModel::addNormalEquations(const std::vector<Pose>& /*poses*/, NormalEquations& /*system*/) const {
  throw Error(std::string("pose graph: a ") + name() + " factor does not form its normal equations");
}

void checkNode(std::size_t node, std::size_t num_poses, const std::string& label) {
  if (node >= num_poses) {
    throw Error(label + " links node " + std::to_string(node) + " but there are " +
                std::to_string(num_poses) + " poses");
  }
}

void checkFinite(const Pose& measurement, const std::string& label) {
  if (!measurement.t.allFinite() || !measurement.q.coeffs().allFinite()) {
    throw Error(label + " has a non-finite measurement");
  }
}

}  // namespace hba::graph
