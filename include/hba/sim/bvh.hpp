#pragma once
// A bounding volume hierarchy over any list of primitives, known only by
// their boxes. Built once with the surface area heuristic (binned), then
// queried from many threads at once (queries are const and lock-free).
#include <cstdint>
#include <optional>
#include <vector>

#include "hba/sim/primitives.hpp"

namespace hba::sim {

struct BvhHit {
  std::uint32_t primitive = 0;
  double distance = 0.0;
};

class Bvh {
 public:
  Bvh() = default;
  explicit Bvh(const std::vector<Aabb>& primitive_bounds);

  // The closest hit in (0, t_max). `intersect(index, t_max)` must return the
  // distance to primitive `index` if it is hit before t_max.
  template <class IntersectFn>
  std::optional<BvhHit> closestHit(const Ray& ray, double t_max, IntersectFn&& intersect) const;

  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t primitiveCount() const { return order_.size(); }

 private:
  struct Node {
    Aabb box;
    std::uint32_t first = 0;  // leaf: first slot in order_; inner: left child (right = +1)
    std::uint32_t count = 0;  // primitives in a leaf; 0 for an inner node
    std::uint8_t axis = 0;    // split axis of an inner node, to visit the near child first
  };
  void split(std::uint32_t node_index, const std::vector<Aabb>& bounds, const std::vector<Vec3>& centers);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // primitive indices, grouped by leaf
};

template <class IntersectFn>
std::optional<BvhHit> Bvh::closestHit(const Ray& ray, double t_max, IntersectFn&& intersect) const {
  std::optional<BvhHit> best;
  if (nodes_.empty()) return best;
  const Vec3 inverse_direction = ray.direction.cwiseInverse();
  std::uint32_t stack[128];  // deeper than any SAH tree of < 2^32 primitives in practice
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.hitBefore(ray.origin, inverse_direction, t_max)) continue;
    if (node.count > 0) {
      for (std::uint32_t slot = node.first; slot < node.first + node.count; ++slot) {
        if (auto t = intersect(order_[slot], t_max)) {
          t_max = *t;
          best = BvhHit{order_[slot], *t};
        }
      }
      continue;
    }
    // Push the far child first so the near one is popped (and shrinks t_max) first.
    const bool left_is_near = ray.direction[node.axis] >= 0.0;
    stack[top++] = left_is_near ? node.first + 1 : node.first;
    stack[top++] = left_is_near ? node.first : node.first + 1;
  }
  return best;
}

}  // namespace hba::sim
