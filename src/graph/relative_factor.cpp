// Relative-pose factors from the BA windows, under the window robust loss.
#include "between_factor_model.hpp"

namespace hba::graph {
namespace {

class RelativeFactorModel final : public BetweenFactorModel {
 public:
  explicit RelativeFactorModel(const RelativePoseFactor& f)
      : BetweenFactorModel(f.from, f.to, f.measurement, f.information) {}
  FactorKind kind() const override { return FactorKind::Relative; }
  const char* name() const override { return "relative"; }
  LossGroup lossGroup() const override { return LossGroup::Window; }
};

}  // namespace

void FactorGraph::add(const RelativePoseFactor& factor) {
  models_.push_back(std::make_shared<const RelativeFactorModel>(factor));
}

}  // namespace hba::graph
