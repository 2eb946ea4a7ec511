#pragma once
// Mean map entropy (MME): how crisp a merged map is. For every map point, the
// differential entropy of a Gaussian fitted to its neighbours within a radius,
//   h = 0.5 * ln det(2 pi e Sigma),
// averaged over the points that have enough neighbours. Double walls and
// blurred surfaces spread the neighbours out and raise it: lower is better.
//
// The defaults (with a 0.1 m centroid-downsampled map) are the one rule set
// that reproduces the reference numbers of the hku1 sequence, -2.97 and
// -2.50 (docs/eval.md records the experiment over all 16 variants).
#include <cstddef>

#include "hba/core/point_cloud.hpp"

namespace hba::eval {

struct MmeSettings {
  double radius = 0.3;             // m; neighbours at distance < radius
  int min_neighbors = 15;          // see strictly_more
  bool strictly_more = true;       // use a point if count > min_neighbors (else >=)
  bool count_query = true;         // the query point is one of its own neighbours
  bool sample_covariance = false;  // divide by n - 1 (default: by n, as PCL does)
};

struct MmeResult {
  double mme = 0.0;        // NaN when no point qualifies
  std::size_t points = 0;  // map points
  std::size_t used = 0;    // points with enough neighbours and det > 0
};

// Runs in parallel (oneTBB); the result does not depend on the thread count:
// per-point entropies are summed in point order.
MmeResult meanMapEntropy(const PointCloud& map, const MmeSettings& settings = {});

}  // namespace hba::eval
