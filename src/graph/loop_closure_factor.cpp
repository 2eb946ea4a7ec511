// Loop-closure factors: the relative-pose residual between any two nodes,
// under their own robust loss.
#include "between_factor_model.hpp"

namespace hba::graph {
namespace {

class LoopClosureFactorModel final : public BetweenFactorModel {
 public:
  explicit LoopClosureFactorModel(const LoopClosureFactor& f)
      : BetweenFactorModel(f.from, f.to, f.measurement, f.information) {}
  FactorKind kind() const override { return FactorKind::LoopClosure; }
  const char* name() const override { return "loop closure"; }
  LossGroup lossGroup() const override { return LossGroup::Loop; }
};

}  // namespace

void FactorGraph::add(const LoopClosureFactor& factor) {
  models_.push_back(std::make_shared<const LoopClosureFactorModel>(factor));
}

}  // namespace hba::graph
