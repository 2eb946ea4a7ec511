#include "hba/closure/closure_graph.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "hba/closure/sessions.hpp"
#include "hba/core/error.hpp"
#include "hba/core/relative_pose_error.hpp"
#include "hba/graph/pose_graph.hpp"

namespace hba::closure {
namespace {

constexpr double kDegree = M_PI / 180.0;

double loopChi2(const graph::LoopClosureFactor& f, const std::vector<Pose>& poses, Vec6& error) {
  error = relativePoseError(f.measurement, poses[f.from], poses[f.to]);
  return error.dot(f.information * error);
}

double priorChi2(const graph::PositionPriorFactor& f, const std::vector<Pose>& poses) {
  const Vec3 e = poses[f.node].t - f.position;
  return e.dot(f.information * e);
}

struct Verdicts {
  std::vector<double> loop_chi2, prior_chi2;
  std::vector<bool> loop_beyond, prior_beyond;  // past the gate (and the loops' tolerance)
};

Verdicts judge(const std::vector<Pose>& poses, const std::vector<graph::LoopClosureFactor>& loops,
               const std::vector<graph::PositionPriorFactor>& priors, const ClosureGraphSettings& s) {
  Verdicts v;
  for (const auto& loop : loops) {
    Vec6 e;
    const double chi2 = loopChi2(loop, poses, e);
    const bool off =
        e.head<3>().norm() > s.loop_tolerance_m || e.tail<3>().norm() > s.loop_tolerance_deg * kDegree;
    v.loop_chi2.push_back(chi2);
    v.loop_beyond.push_back(chi2 > s.loop_gate && off);
  }
  for (const auto& prior : priors) {
    const double chi2 = priorChi2(prior, poses);
    v.prior_chi2.push_back(chi2);
    v.prior_beyond.push_back(chi2 > s.prior_gate);
  }
  return v;
}

// Drops the worst active factors beyond the gate: one loop (a wrong loop
// makes its right neighbours look wrong too, until it is gone), or a tenth
// of the priors beyond it (priors are many and each pulls little).
bool dropWorst(const Verdicts& v, std::vector<bool>& loop_kept, std::vector<bool>& prior_kept) {
  std::size_t worst_loop = loop_kept.size();
  for (std::size_t i = 0; i < loop_kept.size(); ++i) {
    if (loop_kept[i] && v.loop_beyond[i] &&
        (worst_loop == loop_kept.size() || v.loop_chi2[i] > v.loop_chi2[worst_loop])) {
      worst_loop = i;
    }
  }
  if (worst_loop < loop_kept.size()) {
    loop_kept[worst_loop] = false;
    return true;
  }
  std::vector<std::size_t> beyond;
  for (std::size_t i = 0; i < prior_kept.size(); ++i) {
    if (prior_kept[i] && v.prior_beyond[i]) beyond.push_back(i);
  }
  if (beyond.empty()) return false;
  std::sort(beyond.begin(), beyond.end(),
            [&](std::size_t a, std::size_t b) { return v.prior_chi2[a] > v.prior_chi2[b]; });
  const std::size_t drop = std::max<std::size_t>(1, beyond.size() / 10);
  for (std::size_t k = 0; k < drop; ++k) prior_kept[beyond[k]] = false;
  return true;
}

// Brings back dropped factors that now agree well inside the gate.
bool readmit(const Verdicts& v, const ClosureGraphSettings& s, std::vector<bool>& loop_kept,
             std::vector<bool>& prior_kept, std::vector<int>& loop_returns, std::vector<int>& prior_returns) {
  bool any = false;
  for (std::size_t i = 0; i < loop_kept.size(); ++i) {
    if (!loop_kept[i] && !v.loop_beyond[i] && v.loop_chi2[i] < 0.25 * s.loop_gate && loop_returns[i] == 0) {
      loop_kept[i] = true;
      ++loop_returns[i];
      any = true;
    }
  }
  for (std::size_t i = 0; i < prior_kept.size(); ++i) {
    if (!prior_kept[i] && v.prior_chi2[i] < 0.25 * s.prior_gate && prior_returns[i] == 0) {
      prior_kept[i] = true;
      ++prior_returns[i];
      any = true;
    }
  }
  return any;
}

// A rigid move of the input onto the priors, a start the solver can reach
// them from (the priors' frame may be UTM and turned). Refit twice on the
// priors within three times the median distance, so outliers do not steer
// it; only a shift when the priors lie along a line.
Pose rigidMoveOntoPriors(const std::vector<Pose>& input,
                         const std::vector<graph::PositionPriorFactor>& priors) {
  std::vector<std::size_t> used(priors.size());
  for (std::size_t i = 0; i < priors.size(); ++i) used[i] = i;
  Pose move;
  for (int round = 0; round < 3 && !used.empty(); ++round) {
    Eigen::Matrix3Xd from(3, used.size()), to(3, used.size());
    for (std::size_t k = 0; k < used.size(); ++k) {
      from.col(static_cast<Eigen::Index>(k)) = input[priors[used[k]].node].t;
      to.col(static_cast<Eigen::Index>(k)) = priors[used[k]].position;
    }
    const Vec3 centre = from.rowwise().mean();
    const Eigen::JacobiSVD<Eigen::Matrix3Xd> spread(from.colwise() - centre);
    if (used.size() >= 3 && spread.singularValues()(1) > 1.0) {
      move = Pose::fromMatrix(Eigen::umeyama(from, to, false));
    } else {
      move = Pose(Quat::Identity(), to.rowwise().mean() - centre);
    }
    std::vector<double> distance;
    for (std::size_t i = 0; i < priors.size(); ++i) {
      distance.push_back(((move * input[priors[i].node]).t - priors[i].position).norm());
    }
    std::vector<double> sorted = distance;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                     sorted.end());
    const double limit = 3.0 * sorted[sorted.size() / 2] + 1e-9;
    used.clear();
    for (std::size_t i = 0; i < priors.size(); ++i) {
      if (distance[i] <= limit) used.push_back(i);
    }
  }
  return move;
}

}  // namespace

graph::RelativePoseFactor odometryFactor(const std::vector<Pose>& input, std::size_t k,
                                         const OdometryNoise& noise) {
  graph::RelativePoseFactor f;
  f.from = k;
  f.to = k + 1;
  f.measurement = relative(input[k], input[k + 1]);
  const double step = f.measurement.t.norm();
  const double sigma_t = noise.translation_m + noise.translation_per_m * step;
  const double sigma_r = (noise.rotation_deg + noise.rotation_deg_per_m * step) * kDegree;
  f.information.setZero();
  f.information.diagonal() << Vec3::Constant(1.0 / (sigma_t * sigma_t)),
      Vec3::Constant(1.0 / (sigma_r * sigma_r));
  return f;
}

ClosureGraphResult solveClosureGraph(const std::vector<Pose>& input,
                                     const std::vector<graph::LoopClosureFactor>& loops,
                                     const std::vector<graph::PositionPriorFactor>& priors,
                                     const ClosureGraphSettings& settings,
                                     const std::vector<std::size_t>& session_starts) {
  const OdometryNoise& n = settings.odometry;
  if (!(n.translation_m > 0.0) || !(n.rotation_deg > 0.0) || !(n.translation_per_m >= 0.0) ||
      !(n.rotation_deg_per_m >= 0.0)) {
    throw Error("closure graph: odometry sigmas must be positive");
  }
  ClosureGraphResult result;
  result.poses = input;
  result.loop_kept.assign(loops.size(), true);
  result.prior_kept.assign(priors.size(), true);
  if (input.size() < 2 || (loops.empty() && priors.empty())) return result;
  // A graph solved where every factor already holds would move the poses
  // by the loops' own noise only, and a closed map would never be left
  // alone: keep the input.
  const Verdicts at_input = judge(input, loops, priors, settings);
  if (std::none_of(at_input.loop_beyond.begin(), at_input.loop_beyond.end(), [](bool b) { return b; }) &&
      std::none_of(at_input.prior_beyond.begin(), at_input.prior_beyond.end(), [](bool b) { return b; })) {
    result.loop_chi2 = at_input.loop_chi2;
    result.prior_chi2 = at_input.prior_chi2;
    result.held_at_input = true;
    return result;
  }

  const std::vector<std::size_t> session = sessionOfFrames(input.size(), session_starts);
  std::vector<graph::RelativePoseFactor> steps;
  for (std::size_t k = 0; k + 1 < input.size(); ++k) {
    if (session[k] == session[k + 1]) steps.push_back(odometryFactor(input, k, n));
  }
  graph::PoseGraphSettings solver;
  solver.threads = settings.threads;
  solver.max_iterations = 200;

  std::vector<Pose> start = input;
  if (!priors.empty()) {
    const Pose move = rigidMoveOntoPriors(input, priors);
    for (Pose& p : start) p = move * p;
    // A stretch of bad GNSS (multipath) agrees with itself: judged after
    // the steps have bent to it, it would look right. A Cauchy loss on the
    // priors, narrowed from far to near (graduated), lets the steps decide
    // first; the gates below then drop what stays far.
    graph::FactorGraph graph(steps);
    for (const auto& loop : loops) graph.add(loop);
    for (const auto& prior : priors) graph.add(prior);
    solver.prior_robust_loss = graph::RobustLoss::Cauchy;
    for (const double scale : {64.0, 16.0, 4.0}) {
      solver.prior_robust_loss_scale = scale;
      start = graph::optimizeFactorGraph(start, graph, solver).poses;
      ++result.rounds;
    }
  }
  std::vector<int> loop_returns(loops.size(), 0), prior_returns(priors.size(), 0);
  const auto solve = [&] {
    graph::FactorGraph graph(steps);
    for (std::size_t i = 0; i < loops.size(); ++i) {
      if (result.loop_kept[i]) graph.add(loops[i]);
    }
    for (std::size_t i = 0; i < priors.size(); ++i) {
      if (result.prior_kept[i]) graph.add(priors[i]);
    }
    // Every round starts from the same start (the input, on the priors): a
    // solution bent by a dropped factor is no better one.
    result.poses = graph::optimizeFactorGraph(start, graph, solver).poses;
    ++result.rounds;
    return judge(result.poses, loops, priors, settings);
  };
  Verdicts verdicts = solve();
  while (result.rounds < settings.max_rounds) {
    const bool changed =
        dropWorst(verdicts, result.loop_kept, result.prior_kept) ||
        readmit(verdicts, settings, result.loop_kept, result.prior_kept, loop_returns, prior_returns);
    if (!changed) break;
    verdicts = solve();
  }
  result.loop_chi2 = verdicts.loop_chi2;
  result.prior_chi2 = verdicts.prior_chi2;
  return result;
}

ClosureGraphResult anchorToPriors(const std::vector<Pose>& poses,
                                  const std::vector<graph::PositionPriorFactor>& priors,
                                  const ClosureGraphSettings& settings,
                                  const std::vector<std::size_t>& session_starts) {
  ClosureGraphSettings stiff = settings;
  stiff.odometry = finalStepNoise();
  return solveClosureGraph(poses, {}, priors, stiff, session_starts);
}

}  // namespace hba::closure
