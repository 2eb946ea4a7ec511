#pragma once
// A nanoflann k-d tree over a vector of fixed-size float vectors (points in
// 3-D, descriptors in 33-D), read in place through an adaptor.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace hba::closure {

template <int Dim>
class KdTree {
 public:
  using Vector = Eigen::Matrix<float, Dim, 1>;

  // `items` must outlive the tree and stay unchanged.
  explicit KdTree(const std::vector<Vector>& items)
      : adaptor_{items}, tree_(Dim, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree_.buildIndex();
  }

  std::size_t size() const { return adaptor_.items.size(); }

  // The nearest item and its squared distance; {size(), inf} when empty.
  // With `eps` > 0, an item at most (1 + eps) times farther than the nearest
  // (much faster in many dimensions).
  std::pair<std::size_t, float> nearest(const Vector& query, float eps = 0.0F) const {
    std::uint32_t index = 0;
    float distance_sq = std::numeric_limits<float>::infinity();
    if (size() == 0) return {size(), distance_sq};
    nanoflann::KNNResultSet<float, std::uint32_t> result(1);
    result.init(&index, &distance_sq);
    tree_.findNeighbors(result, query.data(), nanoflann::SearchParams(32, eps));
    return {index, distance_sq};
  }

  // Items within `radius` (not squared), in no particular order.
  std::vector<std::pair<std::uint32_t, float>> within(const Vector& query, float radius) const {
    std::vector<std::pair<std::uint32_t, float>> found;
    nanoflann::SearchParams params;
    params.sorted = false;
    tree_.radiusSearch(query.data(), radius * radius, found, params);
    return found;
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

}  // namespace hba::closure
