#include "hba/pipeline/closure_files.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <map>

#include "hba/closure/frame_priors.hpp"
#include "hba/core/error.hpp"
#include "hba/io/loop_file.hpp"
#include "hba/io/position_prior_file.hpp"

namespace hba::pipeline {

pipeline::ClosureInputs readClosureFiles(const ClosureFiles& files,
                                         const std::vector<const Trajectory*>& sessions,
                                         const std::vector<std::size_t>& starts, std::size_t frames) {
  if (starts.size() < sessions.size()) {
    throw Error(
        fmt::format("closure files: {} sessions but {} session starts", sessions.size(), starts.size()));
  }
  pipeline::ClosureInputs inputs;
  if (!files.loops.empty()) {
    for (const io::LoopRecord& record : io::readLoopFile(files.loops, frames)) {
      inputs.loops.push_back({record.from, record.to, record.relative});
    }
    spdlog::info("{}: {} loop closure pairs", files.loops, inputs.loops.size());
  }
  if (files.priors.empty()) return inputs;
  const std::vector<io::TimedPosition> timed = io::readPositionPriorFile(files.priors);
  std::map<std::size_t, std::size_t> session_of_line;  // a prior's file line -> the session it went to
  std::size_t outside = timed.size();
  for (std::size_t k = 0; k < sessions.size(); ++k) {
    closure::FramePriors attached;
    try {
      attached = closure::attachPriors(timed, *sessions[k], files.prior_max_gap_s);
    } catch (const Error& e) {
      throw Error(files.priors + ": " + e.what() +
                  (sessions.size() > 1 ? " (session " + std::to_string(k) + ")" : std::string()));
    }
    for (std::size_t f = 0; f < attached.factors.size(); ++f) {
      const auto [other, fresh] = session_of_line.emplace(attached.lines[f], k);
      if (!fresh) {
        throw Error(
            fmt::format("{}: the prior on line {} falls among the scans of sessions {} and {}: their "
                        "stamps overlap, so priors cannot tell them apart (give each session its own "
                        "clock's stamps)",
                        files.priors, attached.lines[f], other->second, k));
      }
      graph::PositionPriorFactor factor = attached.factors[f];
      factor.node += starts[k];
      inputs.priors.push_back(factor);
    }
    outside -= attached.factors.size();
  }
  spdlog::info("{}: {} position priors, {} attached to frames{}", files.priors, timed.size(),
               inputs.priors.size(),
               sessions.size() > 1 ? fmt::format(" of {} sessions", sessions.size()) : std::string());
  if (outside > 0) {
    spdlog::warn("{}: {} priors lie more than {:g} s from every scan and are not used", files.priors, outside,
                 files.prior_max_gap_s);
  }
  if (inputs.priors.empty()) throw Error(files.priors + ": no prior falls within the scans' time span");
  return inputs;
}

}  // namespace hba::pipeline
