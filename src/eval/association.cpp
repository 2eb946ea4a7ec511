#include "hba/eval/association.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>

#include "hba/core/error.hpp"

namespace hba::eval {

Association associateByIndex(std::size_t reference_count, std::size_t estimate_count) {
  if (reference_count != estimate_count) {
    throw Error("association by index needs equal pose counts, got " + std::to_string(reference_count) +
                " reference and " + std::to_string(estimate_count) +
                " estimated poses (use time association)");
  }
  Association a;
  a.reference.resize(reference_count);
  std::iota(a.reference.begin(), a.reference.end(), std::size_t{0});
  a.estimate = a.reference;
  return a;
}

namespace {

// Index (into `stamps`) of the stamp nearest to t, given `order` sorting stamps.
std::size_t nearestStamp(const std::vector<double>& stamps, const std::vector<std::size_t>& order, double t) {
  const auto it = std::lower_bound(order.begin(), order.end(), t,
                                   [&](std::size_t k, double value) { return stamps[k] < value; });
  if (it == order.end()) return order.back();
  if (it == order.begin()) return *it;
  const std::size_t after = *it, before = *(it - 1);
  return (stamps[after] - t) < (t - stamps[before]) ? after : before;
}

}  // namespace

std::string describeStamps(const std::vector<double>& stamps) {
  if (stamps.empty()) return "no stamps";
  const auto [low, high] = std::minmax_element(stamps.begin(), stamps.end());
  char text[128];
  std::snprintf(text, sizeof text, "%zu stamps from %.3f to %.3f s", stamps.size(), *low, *high);
  return text;
}

Association pairByTime(const std::vector<double>& reference_stamps,
                       const std::vector<double>& estimate_stamps, double max_diff) {
  if (reference_stamps.empty() || estimate_stamps.empty()) {
    throw Error("association by time needs timestamps on both trajectories");
  }
  if (!(max_diff >= 0.0)) throw Error("the time tolerance must be >= 0");
  std::vector<std::size_t> order(reference_stamps.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return reference_stamps[a] < reference_stamps[b]; });

  // Best estimate per reference pose, so a reference pose is used at most once.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> best_estimate(reference_stamps.size(), kNone);
  std::vector<double> best_diff(reference_stamps.size(), std::numeric_limits<double>::infinity());
  for (std::size_t e = 0; e < estimate_stamps.size(); ++e) {
    const std::size_t r = nearestStamp(reference_stamps, order, estimate_stamps[e]);
    const double diff = std::abs(reference_stamps[r] - estimate_stamps[e]);
    if (diff <= max_diff && diff < best_diff[r]) {
      best_diff[r] = diff;
      best_estimate[r] = e;
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (estimate, reference)
  for (std::size_t r = 0; r < best_estimate.size(); ++r) {
    if (best_estimate[r] != kNone) pairs.emplace_back(best_estimate[r], r);
  }
  std::sort(pairs.begin(), pairs.end());
  Association a;
  a.mode = AssociationMode::Time;
  for (const auto& [e, r] : pairs) {
    a.estimate.push_back(e);
    a.reference.push_back(r);
  }
  return a;
}

Association associateByTime(const std::vector<double>& reference_stamps,
                            const std::vector<double>& estimate_stamps, double max_diff) {
  Association a = pairByTime(reference_stamps, estimate_stamps, max_diff);
  if (a.size() == 0) {
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%g", max_diff);
    throw Error(std::string("no timestamps match within ") + tolerance + " s: the reference has " +
                describeStamps(reference_stamps) + ", the estimate " + describeStamps(estimate_stamps));
  }
  return a;
}

bool pairsByTime(const Trajectory& reference, const Trajectory& estimate, AssociationMode mode) {
  return mode == AssociationMode::Time ||
         (mode == AssociationMode::Auto && reference.hasStamps() && estimate.hasStamps());
}

Association associate(const Trajectory& reference, const Trajectory& estimate, AssociationMode mode,
                      double max_time_diff) {
  if (pairsByTime(reference, estimate, mode)) {
    return associateByTime(reference.stamps, estimate.stamps, max_time_diff);
  }
  return associateByIndex(reference.size(), estimate.size());
}

}  // namespace hba::eval
