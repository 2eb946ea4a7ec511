#pragma once
// The factors of one pose graph, of any kind, in the order they were added
// (the order fixes the solver's problem, so it is part of the result).
#include <cstddef>
#include <memory>
#include <vector>

#include "hba/graph/factors.hpp"

namespace hba::graph {

// The solver's view of one factor: residual, cost, checks and what it does to
// the gauge (src/graph/factor_model.hpp). Each factor kind implements it in
// its own source file, which also defines that kind's add().
class FactorModel;

class FactorGraph {
 public:
  FactorGraph() = default;
  // A graph of relative factors only, as the pyramid builds it.
  explicit FactorGraph(const std::vector<RelativePoseFactor>& relative_factors);

  void add(const RelativePoseFactor& factor);
  void add(const LoopClosureFactor& factor);
  void add(const PosePriorFactor& factor);
  void add(const PositionPriorFactor& factor);
  void add(const WindowShapeFactor& factor);

  std::size_t size() const { return models_.size(); }
  bool empty() const { return models_.empty(); }
  std::size_t count(FactorKind kind) const;

  // For the solver; the models are immutable, so copies of a graph share them.
  const std::vector<std::shared_ptr<const FactorModel>>& models() const { return models_; }

 private:
  std::vector<std::shared_ptr<const FactorModel>> models_;
};

}  // namespace hba::graph
