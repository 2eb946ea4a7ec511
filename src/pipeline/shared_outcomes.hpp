#pragma once
// What the first member of a group found, sent to the others (a collective:
// every member calls it).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "closure_stage.hpp"
#include "dist/bytes.hpp"
#include "hba/closure/loop_check.hpp"
#include "hba/core/error.hpp"
#include "hba/dist/group.hpp"
#include "hba/graph/factors.hpp"
#include "pyramid/factor_bytes.hpp"

namespace hba::pipeline {

// The first member's poses, in every member.
std::vector<Pose> posesFromRoot(const dist::Group& group, const std::vector<Pose>& mine);

// The first member's closure outcome (start, loops, priors; its report stays
// there), in every member.
void shareClosures(const dist::Group& group, ClosureOutcome& closed);

// The loop checks of every member, in every member: member r verified the
// candidates k with k % size == r and holds their checks at k in `checks`
// (one entry a candidate); the others' arrive at theirs.
void shareLoopChecks(const dist::Group& group, std::vector<closure::LoopCheck>& checks);

}  // namespace hba::pipeline
