#pragma once
// The factors of one pose graph, of any kind, in the order they were added
// (the order fixes the solver's problem, so it is part of the result).
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "hba/graph/factors.hpp"

namespace hba::graph {

class FactorGraph {
 public:
  FactorGraph() = default;
  // A graph of relative factors only, as the pyramid builds it.
  explicit FactorGraph(const std::vector<RelativePoseFactor>& relative_factors);

  // Any kind of hba/graph/factors.hpp: its modelOf() makes the solver's
  // model (residual, cost, checks, what it does to the gauge).
  template <typename Factor>
  void add(const Factor& factor) {
    models_.push_back(modelOf(factor));
  }

  std::size_t size() const { return models_.size(); }
  bool empty() const { return models_.empty(); }
  // Factors of the kind named ("relative", "loop closure", "pose prior",
  // "position prior", "height prior", "window shape": FactorModel::name()).
  std::size_t count(std::string_view kind) const;

  // For the solver; the models are immutable, so copies of a graph share them.
  const std::vector<std::shared_ptr<const FactorModel>>& models() const { return models_; }

 private:
  std::vector<std::shared_ptr<const FactorModel>> models_;
};

}  // namespace hba::graph
