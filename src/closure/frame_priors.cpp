#include "hba/closure/frame_priors.hpp"

#include <algorithm>
#include <cmath>

#include "hba/core/error.hpp"

namespace hba::closure {
namespace {

// The odometry's position at `stamp` (linear between the frames around it).
Vec3 positionAt(const Trajectory& odometry, std::size_t after, double stamp) {
  if (after == 0) return odometry.poses.front().t;
  if (after >= odometry.size()) return odometry.poses.back().t;
  const double t0 = odometry.stamps[after - 1], t1 = odometry.stamps[after];
  const double a = t1 > t0 ? std::clamp((stamp - t0) / (t1 - t0), 0.0, 1.0) : 0.0;
  return (1.0 - a) * odometry.poses[after - 1].t + a * odometry.poses[after].t;
}

}  // namespace

FramePriors attachPriors(const std::vector<io::TimedPosition>& priors, const Trajectory& odometry,
                         double max_gap_s) {
  if (!odometry.hasStamps() || odometry.stamps.size() != odometry.size()) {
    throw Error(
        "position priors are matched to scans by time, but the sequence has no timestamps "
        "(give its times with --times, or a stamped trajectory)");
  }
  FramePriors out;
  const std::vector<double>& stamps = odometry.stamps;
  for (const io::TimedPosition& prior : priors) {
    const std::size_t after = static_cast<std::size_t>(
        std::lower_bound(stamps.begin(), stamps.end(), prior.stamp) - stamps.begin());
    std::size_t nearest = after;
    if (after == stamps.size() ||
        (after > 0 && prior.stamp - stamps[after - 1] < stamps[after] - prior.stamp)) {
      nearest = after - 1;
    }
    if (!(std::abs(stamps[nearest] - prior.stamp) <= max_gap_s)) {
      ++out.outside;
      continue;
    }
    graph::PositionPriorFactor f;
    f.node = nearest;
    f.position = prior.position + (odometry.poses[nearest].t - positionAt(odometry, after, prior.stamp));
    f.information = prior.sigma.cwiseInverse().cwiseAbs2().asDiagonal();
    out.factors.push_back(f);
    out.lines.push_back(prior.line);
  }
  return out;
}

}  // namespace hba::closure
