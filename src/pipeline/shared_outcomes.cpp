#include "shared_outcomes.hpp"

namespace hba::pipeline {

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
    pyramid::putFactors(out, closed.loops);
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
  closed.loops = pyramid::getFactors<graph::LoopClosureFactor>(in);
  closed.priors.resize(in.get<std::uint64_t>());
  for (graph::PositionPriorFactor& prior : closed.priors) {
    prior.node = in.get<std::uint64_t>();
    prior.position = in.get<Vec3>();
    prior.information = in.get<Mat3>();
  }
}

namespace {

void putCheck(dist::ByteWriter& out, const closure::LoopCheck& check) {
  out.put<std::uint8_t>(check.accepted ? 1 : 0);
  out.putVector(std::vector<char>(check.reason.begin(), check.reason.end()));
  dist::putPose(out, check.relative);
  out.put(check.information);
  out.put<std::uint64_t>(check.shared_planes);
  for (const double value : {check.overlap, check.rms_m, check.correction_m, check.correction_deg,
                             check.search_score, check.search_second_score, check.sigma_m, check.sigma_deg}) {
    out.put(value);
  }
}

closure::LoopCheck getCheck(dist::ByteReader& in) {
  closure::LoopCheck check;
  check.accepted = in.get<std::uint8_t>() != 0;
  const std::vector<char> reason = in.getVector<char>();
  check.reason.assign(reason.begin(), reason.end());
  check.relative = dist::getPose(in);
  check.information = in.get<Mat6>();
  check.shared_planes = in.get<std::uint64_t>();
  for (double* value : {&check.overlap, &check.rms_m, &check.correction_m, &check.correction_deg,
                        &check.search_score, &check.search_second_score, &check.sigma_m, &check.sigma_deg}) {
    *value = in.get<double>();
  }
  return check;
}

}  // namespace

void shareLoopChecks(const dist::Group& group, std::vector<closure::LoopCheck>& checks) {
  const auto size = static_cast<std::size_t>(group.size());
  dist::ByteWriter out;
  for (std::size_t k = static_cast<std::size_t>(group.rank()); k < checks.size(); k += size) {
    putCheck(out, checks[k]);
  }
  const std::vector<dist::Bytes> all = group.allGather(out.take());
  for (std::size_t r = 0; r < all.size(); ++r) {
    if (static_cast<int>(r) == group.rank()) continue;
    dist::ByteReader in(all[r]);
    for (std::size_t k = r; k < checks.size(); k += size) checks[k] = getCheck(in);
    if (!in.done())
      throw Error("closure exchange: member " + std::to_string(r) + " sent more checks than it verified");
  }
}

}  // namespace hba::pipeline
