#include "hba/eval/map_entropy.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/kd_tree.hpp"
#include "core/progress.hpp"
#include "hba/core/error.hpp"

namespace hba::eval {
namespace {

// A radius "result set" that accumulates the moments of the neighbours on the
// fly, relative to the query point (small numbers: no cancellation), instead
// of storing their indices.
class MomentCollector {
 public:
  using DistanceType = float;
  using IndexType = std::uint32_t;

  MomentCollector(const std::vector<Vec3f>& points, const Vec3f& query, float radius_sq,
                  std::uint32_t query_index, bool count_query)
      : points_(points),
        query_(query),
        radius_sq_(radius_sq),
        query_index_(query_index),
        count_query_(count_query) {}

  std::size_t size() const { return count_; }
  bool full() const { return true; }
  float worstDist() const { return radius_sq_; }
  void sort() {}
  bool addPoint(float dist_sq, std::uint32_t index) {
    if (dist_sq >= radius_sq_) return true;
    if (index == query_index_ && !count_query_) return true;
    const Vec3 d = (points_[index] - query_).cast<double>();
    ++count_;
    sum_ += d;
    sum_outer_ += d * d.transpose();
    return true;
  }

  // Covariance with divisor n - 1 (sample) or n (population).
  Mat3 covariance(bool sample) const {
    const double n = static_cast<double>(count_);
    const Mat3 scatter = sum_outer_ - sum_ * sum_.transpose() / n;
    return scatter / (sample ? n - 1.0 : n);
  }

 private:
  const std::vector<Vec3f>& points_;
  Vec3f query_;
  float radius_sq_;
  std::uint32_t query_index_;
  bool count_query_;
  std::size_t count_ = 0;
  Vec3 sum_ = Vec3::Zero();
  Mat3 sum_outer_ = Mat3::Zero();
};

const double kLogTwoPiE = std::log(2.0 * M_PI * M_E);
constexpr double kSkipped = std::numeric_limits<double>::quiet_NaN();

}  // namespace

MmeResult meanMapEntropy(const PointCloud& map, const MmeSettings& settings) {
  if (!(settings.radius > 0.0)) throw Error("MME radius must be > 0");
  if (map.size() >= std::numeric_limits<std::uint32_t>::max()) throw Error("MME: map too large");
  MmeResult result;
  result.points = map.size();
  if (map.empty()) {
    result.mme = kSkipped;
    return result;
  }
  const KdTree<3> tree(map.points, /*leaf_size=*/16);

  // At least 2 points for a sample covariance to exist at all.
  const std::size_t needed = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::max(0, settings.min_neighbors)) + (settings.strictly_more ? 1 : 0));
  const auto radius_sq = static_cast<float>(settings.radius * settings.radius);

  std::vector<double> entropy(map.size(), kSkipped);
  // Seconds at radius 0.3 m, minutes at a few metres: the neighbours grow
  // with the radius squared.
  Progress progress("map entropy", map.size(), "points");
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, map.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        MomentCollector neighbours(map.points, map.points[i], radius_sq,
                                                   static_cast<std::uint32_t>(i), settings.count_query);
                        tree.visit(neighbours, map.points[i]);
                        if (neighbours.size() < needed) continue;
                        const double det = neighbours.covariance(settings.sample_covariance).determinant();
                        // A degenerate (exactly planar or linear) neighbourhood has no finite entropy.
                        if (det > 0.0) entropy[i] = 0.5 * (3.0 * kLogTwoPiE + std::log(det));
                      }
                      progress.advance(range.size());
                    });

  double sum = 0.0;  // in point order: the same result for any thread count
  for (double h : entropy) {
    if (std::isnan(h)) continue;
    sum += h;
    ++result.used;
  }
  result.mme = result.used > 0 ? sum / static_cast<double>(result.used) : kSkipped;
  return result;
}

}  // namespace hba::eval
