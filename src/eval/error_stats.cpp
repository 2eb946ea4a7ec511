#include "hba/eval/error_stats.hpp"

#include <algorithm>
#include <cmath>

namespace hba::eval {

ErrorStats summarize(std::vector<double> errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sum = 0.0, sum_sq = 0.0;
  s.min = errors.front();
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
    s.max = std::max(s.max, e);
    s.min = std::min(s.min, e);
  }
  const double n = static_cast<double>(errors.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double spread = 0.0;  // around the mean: no cancellation as in sum_sq/n - mean^2
  for (double e : errors) spread += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(spread / n);
  const std::size_t mid = errors.size() / 2;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(mid), errors.end());
  s.median = errors[mid];
  if (errors.size() % 2 == 0) {
    const double below = *std::max_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(mid));
    s.median = 0.5 * (s.median + below);
  }
  return s;
}

}  // namespace hba::eval
