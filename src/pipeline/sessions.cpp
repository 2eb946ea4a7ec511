#include "hba/pipeline/sessions.hpp"

#include <spdlog/spdlog.h>

#include "hba/core/error.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"

namespace hba::pipeline {

SessionScans::SessionScans(const std::vector<const io::Dataset*>& datasets,
                           const std::vector<std::string>& names) {
  std::vector<const io::ScanSource*> parts;
  for (std::size_t k = 0; k < datasets.size(); ++k) {
    sources_.push_back(std::make_unique<io::DatasetScanSource>(*datasets[k]));
    parts.push_back(sources_.back().get());
    inputs_.push_back({parts.back(), &datasets[k]->trajectory(), names.at(k)});
  }
  all_ = std::make_unique<io::ConcatenatedScanSource>(parts);
}

std::vector<const Trajectory*> SessionScans::trajectories() const {
  std::vector<const Trajectory*> out;
  for (const SessionInput& input : inputs_) out.push_back(input.trajectory);
  return out;
}

const char* placementName(SessionPlacement::Method method) {
  switch (method) {
    case SessionPlacement::Method::Register:
      return "register";
    case SessionPlacement::Method::Identity:
      return "identity";
    case SessionPlacement::Method::Given:
      break;
  }
  return "given";
}

PlacedSessions placeSessions(const std::vector<SessionInput>& sessions, const SessionPlacement& how,
                             double scan_voxel) {
  PlacedSessions placed;
  placed.world_from_session.assign(sessions.size(), Pose());
  if (sessions.size() < 2) return placed;
  switch (how.method) {
    case SessionPlacement::Method::Identity:
      return placed;
    case SessionPlacement::Method::Given:
      if (how.given.size() != sessions.size() - 1) {
        throw Error("session placement: " + std::to_string(how.given.size()) + " transforms for " +
                    std::to_string(sessions.size() - 1) + " later sessions");
      }
      std::copy(how.given.begin(), how.given.end(), placed.world_from_session.begin() + 1);
      return placed;
    case SessionPlacement::Method::Register:
      break;
  }
  const closure::SessionAlignmentSettings settings;
  for (std::size_t k = 1; k < sessions.size(); ++k) {
    const voxel::DownsampledScanSource reference(*sessions[0].scans, scan_voxel);
    const voxel::DownsampledScanSource session(*sessions[k].scans, scan_voxel);
    const closure::SessionAlignment a = closure::alignSession(
        reference, sessions[0].trajectory->poses, session, sessions[k].trajectory->poses, settings);
    nlohmann::json report = alignmentReport(a, sessions[k].name);
    report["session"] = k;
    placed.registered.push_back(report);
    if (!a.found) {
      throw Error(sessions[k].name + ": could not place this session in " + sessions[0].name + "'s frame (" +
                  a.reason +
                  "); give the transform with --align FILE, or --align identity if they share a frame");
    }
    placed.world_from_session[k] = a.world_from_session;
    spdlog::info("{}: placed in {}'s frame by {} agreeing of {} verified place pairs ({} registered)",
                 sessions[k].name, sessions[0].name, a.agreeing, a.verified, a.tried);
  }
  return placed;
}

std::vector<Pose> sessionsInOneFrame(const std::vector<SessionInput>& sessions, const PlacedSessions& placed,
                                     pipeline::ClosureInputs& closures) {
  std::vector<Pose> initial;
  for (std::size_t k = 0; k < sessions.size(); ++k) {
    if (k > 0) closures.session_starts.push_back(initial.size());
    for (const Pose& p : sessions[k].trajectory->poses)
      initial.push_back(placed.world_from_session.at(k) * p);
  }
  return initial;
}

nlohmann::json alignmentReport(const closure::SessionAlignment& a, const std::string& label) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const closure::SessionPairTrial& t : a.trials) {
    pairs.push_back({{"reference_frame", t.reference_frame},
                     {"session_frame", t.session_frame},
                     {"votes", t.votes},
                     {"descriptor_matches", t.matches},
                     {"ransac_inliers", t.inliers},
                     {"fitness", t.fitness},
                     {"outcome", t.outcome}});
    spdlog::debug("{}: place {} against reference place {}: {}", label, t.session_frame, t.reference_frame,
                  t.outcome);
  }
  return {{"places", {a.reference_places, a.session_places}},
          {"descriptor_voxel_m", a.feature_voxel_m},
          {"registered", a.tried},
          {"verified", a.verified},
          {"agreeing", a.agreeing},
          {"found", a.found},
          {"seconds",
           {{"describing", a.seconds_describing},
            {"voting", a.seconds_voting},
            {"registering", a.seconds_registering}}},
          {"pairs", pairs}};
}

SessionsRun runSessions(const SessionScans& scans, const SessionPlacement& how, const Plan& plan,
                        ClosureInputs& closures) {
  SessionsRun run;
  run.placed = placeSessions(scans.inputs(), how, plan.settings.scan_voxel);
  run.initial = sessionsInOneFrame(scans.inputs(), run.placed, closures);
  spdlog::info("{} sessions, {} scans in all", scans.inputs().size(), scans.all().size());
  run.result = runHierarchicalBa(scans.all(), run.initial, plan, closures);
  return run;
}

}  // namespace hba::pipeline
