#pragma once
// Several sessions of one place, each in its own frame, optimized as one
// sequence in the first session's frame (docs/closure.md, "Several
// sessions"). `hba optimize A B ...` and hba.optimize_sessions make the same
// calls: readClosureFiles, then runSessions (placeSessions,
// sessionsInOneFrame, runHierarchicalBa on the sessions' scans one after
// the other).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hba/closure/session_alignment.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/closure_inputs.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"

namespace hba::pipeline {

struct SessionInput {
  const io::ScanSource* scans = nullptr;
  const Trajectory* trajectory = nullptr;  // its poses, in its own frame
  std::string name;                        // for messages (its folder)
};

// The sessions' scans read from their datasets: all of them one after the
// other, and each session as placeSessions takes it, named `names[k]`.
class SessionScans {
 public:
  SessionScans(const std::vector<const io::Dataset*>& datasets, const std::vector<std::string>& names);
  const io::ConcatenatedScanSource& all() const { return *all_; }
  const std::vector<SessionInput>& inputs() const { return inputs_; }
  std::vector<const Trajectory*> trajectories() const;

 private:
  std::vector<std::unique_ptr<io::DatasetScanSource>> sources_;
  std::unique_ptr<io::ConcatenatedScanSource> all_;
  std::vector<SessionInput> inputs_;
};

// How the later sessions are placed in the first one's frame.
struct SessionPlacement {
  enum class Method { Register, Identity, Given };
  Method method = Method::Register;
  std::vector<Pose> given;  // Given: world_from_session of each later session
};

// "register", "identity" or "given": report.json's alignment.method.
const char* placementName(SessionPlacement::Method method);

struct PlacedSessions {
  std::vector<Pose> world_from_session;                 // of each session; the first's is the identity
  nlohmann::json registered = nlohmann::json::array();  // each registered session's search
};

// Registers each later session against the first (closure::alignSession,
// the scans downsampled to `scan_voxel`), or takes the identity or the
// transforms given. Throws hba::Error naming a session that registration
// cannot place, or a count of given transforms that does not match.
PlacedSessions placeSessions(const std::vector<SessionInput>& sessions, const SessionPlacement& how,
                             double scan_voxel);

// Every session's poses moved into the first one's frame, one session after
// the other; `closures.session_starts` gets each later session's first frame.
std::vector<Pose> sessionsInOneFrame(const std::vector<SessionInput>& sessions, const PlacedSessions& placed,
                                     pipeline::ClosureInputs& closures);

// Several sessions as one run: each later one placed in the first one's
// frame (`how`), then the method over all their scans by `plan` (planRun
// over scans.all()). `closures` gets each later session's first frame.
struct SessionsRun {
  PlacedSessions placed;
  std::vector<Pose> initial;  // every session's poses in the first one's frame: the run's start
  HbaResult result;           // every session's poses, one after the other
};
SessionsRun runSessions(const SessionScans& scans, const SessionPlacement& how, const Plan& plan,
                        ClosureInputs& closures);

// A registration's search for report.json (its places, pairs and verdicts);
// each pair is logged at debug level under `label`.
nlohmann::json alignmentReport(const closure::SessionAlignment& a, const std::string& label);

}  // namespace hba::pipeline
