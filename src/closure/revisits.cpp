#include "hba/closure/revisits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hba/closure/sessions.hpp"
#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

void validate(const RevisitSettings& s) {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw Error(std::string("revisit detection: ") + name + " must be > 0");
  };
  const auto non_negative = [](double v, const char* name) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw Error(std::string("revisit detection: ") + name + " must be >= 0");
  };
  non_negative(s.drift, "drift");
  non_negative(s.drift_deg_per_m, "drift_deg_per_m");
  positive(s.reach_m, "reach_m");
  positive(s.min_separation_m, "min_separation_m");
  positive(s.spacing_m, "spacing_m");
  non_negative(s.max_search_m, "max_search_m");
  non_negative(s.max_search_deg, "max_search_deg");
}

}  // namespace

std::vector<double> cumulativePath(const std::vector<Pose>& poses) {
  std::vector<double> s(poses.size(), 0.0);
  for (std::size_t k = 1; k < poses.size(); ++k) s[k] = s[k - 1] + (poses[k].t - poses[k - 1].t).norm();
  return s;
}

DriftSearch driftSearch(double path_m, const RevisitSettings& settings) {
  return {std::min(settings.drift * path_m, settings.max_search_m),
          std::min(settings.drift_deg_per_m * path_m, settings.max_search_deg)};
}

std::vector<RevisitCandidate> findRevisits(const std::vector<Pose>& poses, const RevisitSettings& settings,
                                           const std::vector<std::size_t>& session_starts) {
  validate(settings);
  const std::vector<double> s = cumulativePath(poses);
  const std::vector<std::size_t> session = sessionOfFrames(poses.size(), session_starts);
  std::vector<RevisitCandidate> found;
  double next_sample = 0.0;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    if (s[j] < next_sample) continue;
    // The earlier frame that is nearest relative to what drift allows.
    RevisitCandidate best;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < j; ++i) {
      const bool other_session = session[i] != session[j];
      if (!other_session && s[j] - s[i] < settings.min_separation_m) continue;
      const double path = s[j] - s[i];
      const DriftSearch drift = driftSearch(path, settings);
      const double slack = other_session ? settings.max_search_m : drift.radius_m;
      const double distance = (poses[j].t - poses[i].t).norm();
      const double ratio = distance / (settings.reach_m + slack);
      if (ratio <= 1.0 && ratio < best_ratio) {
        best_ratio = ratio;
        best.from = i;
        best.to = j;
        best.path_m = path;
        best.distance_m = distance;
        best.search_radius_m = slack;
        best.search_yaw_deg = other_session ? settings.max_search_deg : drift.yaw_deg;
        best.cross_session = other_session;
      }
    }
    if (std::isfinite(best_ratio)) {
      found.push_back(best);
      next_sample = s[j] + settings.spacing_m;
    }
  }
  return found;
}

}  // namespace hba::closure
