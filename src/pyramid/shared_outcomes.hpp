#pragma once
// What the first member of a group found, sent to the others (a collective:
// every member calls it), and the packing of pose-graph factors that the
// exchanges between members share.
#include <cstdint>
#include <vector>

#include "closure_stage.hpp"
#include "hba/dist/bytes.hpp"
#include "hba/dist/group.hpp"

namespace hba::pyramid {

// A factor between two nodes (relative pose or loop closure): its nodes,
// measurement and 6x6 information.
template <typename Factor>
void putFactors(dist::ByteWriter& out, const std::vector<Factor>& factors) {
  out.put<std::uint64_t>(factors.size());
  for (const Factor& f : factors) {
    out.put<std::uint64_t>(f.from);
    out.put<std::uint64_t>(f.to);
    dist::putPose(out, f.measurement);
    out.put(f.information);
  }
}

template <typename Factor>
std::vector<Factor> getFactors(dist::ByteReader& in) {
  std::vector<Factor> factors(in.get<std::uint64_t>());
  for (Factor& f : factors) {
    f.from = in.get<std::uint64_t>();
    f.to = in.get<std::uint64_t>();
    f.measurement = dist::getPose(in);
    f.information = in.get<Mat6>();
  }
  return factors;
}

// The first member's poses, in every member.
std::vector<Pose> posesFromRoot(const dist::Group& group, const std::vector<Pose>& mine);

// The first member's closure outcome (start, loops, priors; its report stays
// there), in every member.
void shareClosures(const dist::Group& group, ClosureOutcome& closed);

}  // namespace hba::pyramid
