#include "shared_outcomes.hpp"

namespace hba::pyramid {

std::vector<Pose> posesFromRoot(const dist::Group& group, const std::vector<Pose>& mine) {
  dist::ByteWriter out;
  if (group.root()) dist::putPoses(out, mine);
  const dist::Bytes bytes = dist::fromRoot(group, out.take());
  dist::ByteReader in(bytes);
  return dist::getPoses(in);
}

void shareClosures(const dist::Group& group, ClosureOutcome& closed) {
  dist::ByteWriter out;
  if (group.root()) {
    dist::putPoses(out, closed.start);
    putFactors(out, closed.loops);
    out.put<std::uint64_t>(closed.priors.size());
    for (const graph::PositionPriorFactor& prior : closed.priors) {
      out.put<std::uint64_t>(prior.node);
      out.put(prior.position);
      out.put(prior.information);
    }
  }
  const dist::Bytes bytes = dist::fromRoot(group, out.take());
  if (group.root()) return;
  dist::ByteReader in(bytes);
  closed.start = dist::getPoses(in);
  closed.loops = getFactors<graph::LoopClosureFactor>(in);
  closed.priors.resize(in.get<std::uint64_t>());
  for (graph::PositionPriorFactor& prior : closed.priors) {
    prior.node = in.get<std::uint64_t>();
    prior.position = in.get<Vec3>();
    prior.information = in.get<Mat3>();
  }
}

}  // namespace hba::pyramid
