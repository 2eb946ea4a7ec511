#include "hba/sim/bvh.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace hba::sim {
namespace {

constexpr std::uint32_t kMaxLeafSize = 4;
constexpr int kBinCount = 16;
// Relative cost of one box test versus one primitive test in the heuristic.
constexpr double kTraversalCost = 1.0;

struct Bin {
  Aabb box;
  std::uint32_t count = 0;
};

struct SplitChoice {
  int axis = -1;
  double position = 0.0;
  double cost = 0.0;
};

// Best binned-SAH split of order[first, first+count) by primitive centers.
SplitChoice bestSplit(const std::vector<std::uint32_t>& order, std::uint32_t first, std::uint32_t count,
                      const std::vector<Aabb>& bounds, const std::vector<Vec3>& centers) {
  Aabb centroid_box;
  for (std::uint32_t i = first; i < first + count; ++i) centroid_box.grow(centers[order[i]]);
  SplitChoice best;
  best.cost = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = centroid_box.min[axis];
    const double extent = centroid_box.max[axis] - lo;
    if (extent <= 0.0) continue;
    std::array<Bin, kBinCount> bins;
    const double scale = kBinCount / extent;
    for (std::uint32_t i = first; i < first + count; ++i) {
      const std::uint32_t p = order[i];
      const int b = std::min(kBinCount - 1, static_cast<int>((centers[p][axis] - lo) * scale));
      bins[b].box.grow(bounds[p]);
      ++bins[b].count;
    }
    // Sweep from both sides: cost of splitting after bin b.
    std::array<double, kBinCount - 1> left_cost{};
    Aabb left_box;
    std::uint32_t left_count = 0;
    for (int b = 0; b < kBinCount - 1; ++b) {
      left_box.grow(bins[b].box);
      left_count += bins[b].count;
      left_cost[b] = left_count * left_box.surfaceArea();
    }
    Aabb right_box;
    std::uint32_t right_count = 0;
    for (int b = kBinCount - 1; b > 0; --b) {
      right_box.grow(bins[b].box);
      right_count += bins[b].count;
      const double cost = left_cost[b - 1] + right_count * right_box.surfaceArea();
      if (right_count < count && cost < best.cost) {
        best = SplitChoice{axis, lo + b / scale, cost};
      }
    }
  }
  return best;
}

}  // namespace

Bvh::Bvh(const std::vector<Aabb>& primitive_bounds) {
  if (primitive_bounds.empty()) return;
  order_.resize(primitive_bounds.size());
  std::iota(order_.begin(), order_.end(), 0u);
  std::vector<Vec3> centers(primitive_bounds.size());
  for (std::size_t i = 0; i < primitive_bounds.size(); ++i) {
    centers[i] = primitive_bounds[i].center();
  }
  nodes_.reserve(2 * primitive_bounds.size());
  Node root;
  root.first = 0;
  root.count = static_cast<std::uint32_t>(order_.size());
  nodes_.push_back(root);
  split(0, primitive_bounds, centers);
}

void Bvh::split(std::uint32_t node_index, const std::vector<Aabb>& bounds, const std::vector<Vec3>& centers) {
  // Iterative, so deep unbalanced trees cannot overflow the call stack.
  std::vector<std::uint32_t> pending{node_index};
  while (!pending.empty()) {
    const std::uint32_t index = pending.back();
    pending.pop_back();
    const std::uint32_t first = nodes_[index].first;
    const std::uint32_t count = nodes_[index].count;
    Aabb box;
    for (std::uint32_t i = first; i < first + count; ++i) box.grow(bounds[order_[i]]);
    nodes_[index].box = box;
    if (count <= kMaxLeafSize) continue;

    const SplitChoice choice = bestSplit(order_, first, count, bounds, centers);
    const double leaf_cost = count * box.surfaceArea();
    if (choice.axis < 0 || kTraversalCost * box.surfaceArea() + choice.cost >= leaf_cost) {
      continue;  // splitting would not pay off (or all centers coincide)
    }
    const auto middle =
        std::partition(order_.begin() + first, order_.begin() + first + count,
                       [&](std::uint32_t p) { return centers[p][choice.axis] < choice.position; });
    const auto left_count = static_cast<std::uint32_t>(middle - (order_.begin() + first));
    if (left_count == 0 || left_count == count) continue;

    const auto left = static_cast<std::uint32_t>(nodes_.size());
    Node left_node;
    left_node.first = first;
    left_node.count = left_count;
    Node right_node;
    right_node.first = first + left_count;
    right_node.count = count - left_count;
    nodes_.push_back(left_node);
    nodes_.push_back(right_node);
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_[index].axis = static_cast<std::uint8_t>(choice.axis);
    pending.push_back(left);
    pending.push_back(left + 1);
  }
}

}  // namespace hba::sim
