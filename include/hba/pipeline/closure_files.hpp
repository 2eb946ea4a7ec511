#pragma once
// Loop pairs and position priors given as files (docs/closure.md, "Files"),
// read into what the method takes: the tool's --loops and --priors and
// hba.optimize(loops=, priors=) read them with this one call.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"  // Trajectory
#include "hba/pipeline/closure_inputs.hpp"

namespace hba::pipeline {

struct ClosureFiles {
  std::string loops;   // loop pairs (io::readLoopFile); "" = none
  std::string priors;  // position priors (io::readPositionPriorFile); "" = none
  // A prior goes to the frame nearest in time, at most this far (s).
  double prior_max_gap_s = 0.5;
};

// Reads both, before any work, so that a bad file fails at once (hba::Error
// naming the file). Loop indices are of all `frames` frames. Several
// sessions are one sequence: session k's stamped poses are `sessions[k]`,
// its first frame `starts[k]` (an entry beyond the sessions, the frame
// count, is ignored), and each prior goes, by its stamp, to the
// session whose scans it falls among. Logs what it read.
pipeline::ClosureInputs readClosureFiles(const ClosureFiles& files,
                                         const std::vector<const Trajectory*>& sessions,
                                         const std::vector<std::size_t>& starts, std::size_t frames);

}  // namespace hba::pipeline
