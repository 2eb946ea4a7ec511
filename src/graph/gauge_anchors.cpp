#include "gauge_anchors.hpp"

#include <numeric>

namespace hba::graph {
namespace {

// Union-find whose representative is always the smallest index of its set.
class SmallestRootSets {
 public:
  explicit SmallestRootSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t root(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    const std::size_t ra = root(a);
    const std::size_t rb = root(b);
    if (ra < rb) parent_[rb] = ra;
    if (rb < ra) parent_[ra] = rb;
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace

std::vector<std::size_t> gaugeAnchors(std::size_t num_nodes,
                                      const std::vector<RelativePoseFactor>& factors) {
  SmallestRootSets sets(num_nodes);
  std::vector<bool> touched(num_nodes, false);
  for (const RelativePoseFactor& f : factors) {
    sets.join(f.from, f.to);
    touched[f.from] = touched[f.to] = true;
  }
  std::vector<std::size_t> anchors;
  for (std::size_t i = 0; i < num_nodes; ++i) {
    if (touched[i] && sets.root(i) == i) anchors.push_back(i);
  }
  return anchors;
}

}  // namespace hba::graph
