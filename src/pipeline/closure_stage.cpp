#include "closure_stage.hpp"

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/stopwatch.hpp"
#include "hba/closure/closure_graph.hpp"
#include "hba/closure/loop_check.hpp"
#include "hba/closure/revisits.hpp"
#include "hba/closure/sessions.hpp"
#include "shared_outcomes.hpp"

namespace hba::pipeline {
namespace {

struct Candidate {
  closure::LoopPair pair;
  const char* source = "file";
  double search_radius_m = 0.0;
  double search_yaw_deg = 0.0;
  std::optional<closure::LoopEnds> ends;
};

// A pair from the caller without a relative pose is placed by the poses,
// which may have drifted as much as a revisit's: it gets the same search.
Candidate fromCaller(const closure::LoopPair& pair, const std::vector<double>& path,
                     const closure::RevisitSettings& revisit) {
  Candidate c;
  c.pair = pair;
  if (!pair.relative) {
    const closure::DriftSearch search =
        closure::driftSearch(std::abs(path[pair.to] - path[pair.from]), revisit);
    c.search_radius_m = search.radius_m;
    c.search_yaw_deg = search.yaw_deg;
  }
  return c;
}

LoopReport describe(const Candidate& c, const closure::LoopCheck& check) {
  LoopReport r;
  r.from = c.pair.from;
  r.to = c.pair.to;
  r.source = c.source;
  r.verified = check.accepted;
  r.reason = check.reason;
  r.shared_planes = check.shared_planes;
  r.overlap = check.overlap;
  r.rms_m = check.rms_m;
  r.correction_m = check.correction_m;
  r.correction_deg = check.correction_deg;
  return r;
}

// With several sessions, each end's neighbourhood stays in its own session:
// the frames across a session start are in no odometry relation to it.
closure::LoopEnds keptInSessions(const closure::LoopPair& pair, const std::vector<std::size_t>& session_of,
                                 std::size_t half_width) {
  const auto range = [&](std::size_t end) {
    std::size_t first = end > half_width ? end - half_width : 0;
    std::size_t last = std::min(session_of.size() - 1, end + half_width);
    while (session_of[first] != session_of[end]) ++first;
    while (session_of[last] != session_of[end]) --last;
    return std::make_pair(first, last);
  };
  return {range(pair.from), range(pair.to)};
}

// The candidates: the caller's pairs, then the revisits the poses come
// back to (`searched` of them: all when asked, those between sessions
// always).
std::vector<Candidate> gatherCandidates(const std::vector<Pose>& initial, const ClosureInputs& closures,
                                        const HbaSettings& settings, ClosureReport& report,
                                        std::size_t& searched) {
  const std::vector<double> path = closure::cumulativePath(initial);
  std::vector<Candidate> candidates;
  for (const closure::LoopPair& pair : closures.loops) {
    candidates.push_back(fromCaller(pair, path, settings.revisit));
  }
  const std::vector<closure::RevisitCandidate> revisits =
      closure::findRevisits(initial, settings.revisit, closures.session_starts);
  report.revisit_candidates = revisits.size();
  searched = 0;
  for (const closure::RevisitCandidate& r : revisits) {
    // Sessions are joined by their revisits: searched whether or not asked.
    if (settings.revisits || r.cross_session) {
      Candidate c;
      c.pair.from = r.from;
      c.pair.to = r.to;
      c.source = r.cross_session ? "sessions" : "revisit";
      c.search_radius_m = r.search_radius_m;
      c.search_yaw_deg = r.search_yaw_deg;
      candidates.push_back(c);
      ++searched;
    }
  }
  if (!settings.revisits && searched < revisits.size()) {
    spdlog::info(
        "the poses come back to {} earlier places (by a drift bound of {:g} %), not searched "
        "(--no-revisits)",
        revisits.size() - searched, 100.0 * settings.revisit.drift);
  }
  return candidates;
}

// Each candidate verified by the plane BA. The verifications are
// independent: their order of finishing changes nothing, nor which member
// of the group ran them (member r takes the candidates k with k % size ==
// r: neighbours along the path, alike in cost, go to different members).
std::vector<closure::LoopCheck> verifyCandidates(const io::ScanSource& clouds,
                                                 const std::vector<Pose>& initial,
                                                 std::vector<Candidate>& candidates,
                                                 const std::vector<std::size_t>& session_starts,
                                                 const HbaSettings& settings, const dist::Group& group) {
  if (!session_starts.empty()) {
    const std::vector<std::size_t> session_of = closure::sessionOfFrames(initial.size(), session_starts);
    for (Candidate& c : candidates) {
      if (c.pair.from < initial.size() && c.pair.to < initial.size()) {
        c.ends = keptInSessions(c.pair, session_of, closure::LoopCheckSettings{}.neighbourhood_frames);
      }
    }
  }
  std::vector<closure::LoopCheck> checks(candidates.size());
  const auto members = static_cast<std::size_t>(group.size());
  const auto mine = static_cast<std::size_t>(group.rank());
  const std::size_t own = candidates.size() > mine ? (candidates.size() - mine + members - 1) / members : 0;
  tbb::parallel_for(std::size_t{0}, own, [&](std::size_t j) {
    const std::size_t i = mine + j * members;
    closure::LoopCheckSettings check;
    check.search_radius_m = candidates[i].search_radius_m;
    check.search_yaw_deg = candidates[i].search_yaw_deg;
    check.information = settings.information;
    checks[i] = closure::verifyLoop(clouds, initial, candidates[i].pair, check, candidates[i].ends);
  });
  if (members > 1) shareLoopChecks(group, checks);
  return checks;
}

// The verified loops and the priors, with the input's own steps, in one
// pose graph: those it keeps (consistent with the rest) close the start.
void closeVerified(const std::vector<Pose>& initial, const ClosureInputs& closures,
                   const std::vector<Candidate>& candidates, const std::vector<closure::LoopCheck>& checks,
                   const HbaSettings& settings, ClosureOutcome& out) {
  ClosureReport& report = out.report;
  std::vector<graph::LoopClosureFactor> verified;
  std::vector<std::size_t> verified_index;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    report.loops.push_back(describe(candidates[i], checks[i]));
    if (!checks[i].accepted) {
      ++report.rejected_by_planes;
      continue;
    }
    ++report.verified;
    graph::LoopClosureFactor f;
    f.from = candidates[i].pair.from;
    f.to = candidates[i].pair.to;
    f.measurement = checks[i].relative;
    f.information = checks[i].information;
    verified.push_back(f);
    verified_index.push_back(i);
  }
  closure::ClosureGraphSettings graph_settings;
  graph_settings.threads = settings.threads;
  const closure::ClosureGraphResult solved =
      closure::solveClosureGraph(initial, verified, closures.priors, graph_settings, closures.session_starts);
  for (std::size_t k = 0; k < verified.size(); ++k) {
    LoopReport& r = report.loops[verified_index[k]];
    if (solved.loop_kept[k]) {
      r.used = true;
      out.loops.push_back(verified[k]);
    } else {
      r.reason = "contradicted by the other loops and priors";
      ++report.dropped_as_inconsistent;
    }
  }
  for (std::size_t k = 0; k < closures.priors.size(); ++k) {
    if (solved.prior_kept[k]) out.priors.push_back(closures.priors[k]);
  }
  report.loops_used = out.loops.size();
  report.priors_used = out.priors.size();
  report.priors_dropped = closures.priors.size() - out.priors.size();
  out.start = solved.poses;
  report.held_at_input = solved.held_at_input;
  report.largest_move_m = largestChange(initial, out.start).translation_m;
}

void logClosures(const ClosureReport& report, std::size_t candidates, std::size_t searched) {
  spdlog::info(
      "closures: {} candidates ({} from the caller, {} revisits), {} verified, {} used; {} priors "
      "used of {}; poses moved up to {:.3f} m, {:.2f} s",
      candidates, report.loops_given, searched, report.verified, report.loops_used, report.priors_used,
      report.priors_given, report.largest_move_m, report.seconds);
  if (report.held_at_input) {
    spdlog::info("  every loop and prior already holds at the input poses: nothing to close, none moved");
  }
  if (report.rejected_by_planes > 0) {
    spdlog::info("  {} loop candidates not supported by the planes (report.json: closure.loops)",
                 report.rejected_by_planes);
  }
  if (report.dropped_as_inconsistent > 0 || report.priors_dropped > 0) {
    spdlog::warn("  dropped as contradicted by the rest: {} loops, {} priors", report.dropped_as_inconsistent,
                 report.priors_dropped);
  }
}

}  // namespace

ClosureOutcome runClosureStage(const io::ScanSource& clouds, const std::vector<Pose>& initial,
                               const ClosureInputs& closures, const HbaSettings& settings,
                               const dist::Group& group) {
  const auto start = Clock::now();
  ClosureOutcome out;
  out.start = initial;
  ClosureReport& report = out.report;
  report.loops_given = closures.loops.size();
  report.priors_given = closures.priors.size();
  report.revisits_searched = settings.revisits;
  std::size_t searched = 0;
  std::vector<Candidate> candidates = gatherCandidates(initial, closures, settings, report, searched);
  if (candidates.empty() && closures.priors.empty() && closures.session_starts.empty()) return out;
  report.ran = true;
  const std::vector<closure::LoopCheck> checks =
      verifyCandidates(clouds, initial, candidates, closures.session_starts, settings, group);
  // The pose graph and the report in the first member (shareClosures sends its outcome).
  if (!group.root()) return out;
  closeVerified(initial, closures, candidates, checks, settings, out);
  report.seconds = secondsSince(start);
  logClosures(report, candidates.size(), searched);
  return out;
}

}  // namespace hba::pipeline
