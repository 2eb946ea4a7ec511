#pragma once
// The project's one k-d tree: nanoflann over a vector of fixed-size float
// vectors (points in 3-D, descriptors in 33-D), read in place. It is also the
// one place that knows nanoflann's versions: 1.4 (Debian 12) through 1.7
// (Debian 13) and later. 1.5 renamed SearchParams to SearchParameters and
// changed radiusSearch's output type; 1.6 calls a result set's sort() and
// reads its DistanceType. Every search here goes through findNeighbors with
// a result set of our own, which all those versions accept alike.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace hba {

namespace kd_tree_detail {

// nanoflann 1.4 reports its version as 0x142; the rename came with 0x150.
#if NANOFLANN_VERSION >= 0x150
using SearchOptions = nanoflann::SearchParameters;
inline SearchOptions searchOptions(float eps) { return SearchOptions(eps, /*sorted=*/false); }
#else
using SearchOptions = nanoflann::SearchParams;
inline SearchOptions searchOptions(float eps) {
  return SearchOptions(/*checks, ignored=*/32, eps, /*sorted=*/false);
}
#endif

// The items within a squared radius, in the order the tree visits them.
struct WithinResults {
  using DistanceType = float;
  using IndexType = std::uint32_t;
  float radius_sq;
  std::vector<std::pair<std::uint32_t, float>>& found;

  std::size_t size() const { return found.size(); }
  bool full() const { return true; }
  float worstDist() const { return radius_sq; }
  void sort() {}
  bool addPoint(float distance_sq, std::uint32_t index) {
    if (distance_sq < radius_sq) found.emplace_back(index, distance_sq);
    return true;
  }
};

// The nearest item.
struct NearestResult {
  using DistanceType = float;
  using IndexType = std::uint32_t;
  std::uint32_t index = 0;
  float distance_sq = std::numeric_limits<float>::infinity();
  bool found = false;

  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return found; }
  float worstDist() const { return distance_sq; }
  void sort() {}
  bool addPoint(float candidate_sq, std::uint32_t candidate) {
    if (candidate_sq < distance_sq) {
      distance_sq = candidate_sq;
      index = candidate;
      found = true;
    }
    return true;
  }
};

}  // namespace kd_tree_detail

template <int Dim>
class KdTree {
 public:
  using Vector = Eigen::Matrix<float, Dim, 1>;

  // `items` must outlive the tree and stay unchanged. The leaf size changes
  // the speed of exact searches, and which item an approximate one returns.
  explicit KdTree(const std::vector<Vector>& items, std::size_t leaf_size = 10)
      : adaptor_{items}, tree_(Dim, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(leaf_size)) {}

  std::size_t size() const { return adaptor_.items.size(); }

  // The nearest item and its squared distance; {size(), inf} when empty.
  // With `eps` > 0, an item at most (1 + eps) times farther than the nearest
  // (much faster in many dimensions).
  std::pair<std::size_t, float> nearest(const Vector& query, float eps = 0.0F) const {
    kd_tree_detail::NearestResult result;
    if (size() == 0) return {size(), result.distance_sq};
    tree_.findNeighbors(result, query.data(), kd_tree_detail::searchOptions(eps));
    return {result.index, result.distance_sq};
  }

  // Items within `radius` (not squared), in no particular order.
  std::vector<std::pair<std::uint32_t, float>> within(const Vector& query, float radius) const {
    std::vector<std::pair<std::uint32_t, float>> found;
    kd_tree_detail::WithinResults results{radius * radius, found};
    visit(results, query);
    return found;
  }

  // Hands each item the tree reaches to `visitor`, a nanoflann result set:
  // DistanceType, full(), worstDist() (squared), addPoint(distance_sq,
  // index) and sort(), which is called where nanoflann sorts and may do
  // nothing. Exact search.
  template <class Visitor>
  void visit(Visitor& visitor, const Vector& query) const {
    if (size() == 0) return;
    tree_.findNeighbors(visitor, query.data(), kd_tree_detail::searchOptions(0.0F));
  }

 private:
  struct Adaptor {
    const std::vector<Vector>& items;
    std::size_t kdtree_get_point_count() const { return items.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t dim) const { return items[i][static_cast<int>(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, Dim,
                                                   std::uint32_t>;
  Adaptor adaptor_;
  Tree tree_;
};

}  // namespace hba
