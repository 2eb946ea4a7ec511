#pragma once
// What the first member of a group found, sent to the others (a collective:
// every member calls it), and the packing of pose-graph factors that the
// exchanges between members share.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "closure_stage.hpp"
#include "dist/bytes.hpp"
#include "hba/closure/loop_check.hpp"
#include "hba/core/error.hpp"
#include "hba/dist/group.hpp"
#include "hba/graph/factors.hpp"

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

// Whole-window factors: nodes, measurements and the dense information.
inline void putShapes(dist::ByteWriter& out, const std::vector<graph::WindowShapeFactor>& shapes) {
  out.put<std::uint64_t>(shapes.size());
  for (const graph::WindowShapeFactor& f : shapes) {
    out.putVector(std::vector<std::uint64_t>(f.nodes.begin(), f.nodes.end()));
    dist::putPoses(out, f.relative);
    out.putVector(std::vector<double>(f.information.data(), f.information.data() + f.information.size()));
  }
}

inline std::vector<graph::WindowShapeFactor> getShapes(dist::ByteReader& in) {
  std::vector<graph::WindowShapeFactor> shapes(in.get<std::uint64_t>());
  for (graph::WindowShapeFactor& f : shapes) {
    const auto nodes = in.getVector<std::uint64_t>();
    f.nodes.assign(nodes.begin(), nodes.end());
    f.relative = dist::getPoses(in);
    const auto numbers = in.getVector<double>();
    const auto size = static_cast<Eigen::Index>(6 * f.relative.size());
    if (static_cast<Eigen::Index>(numbers.size()) != size * size) {
      throw Error("window exchange: a window-shape factor's information has the wrong size");
    }
    f.information = Eigen::Map<const Eigen::MatrixXd>(numbers.data(), size, size);
  }
  return shapes;
}

// The first member's poses, in every member.
std::vector<Pose> posesFromRoot(const dist::Group& group, const std::vector<Pose>& mine);

// The first member's closure outcome (start, loops, priors; its report stays
// there), in every member.
void shareClosures(const dist::Group& group, ClosureOutcome& closed);

// The loop checks of every member, in every member: member r verified the
// candidates k with k % size == r and holds their checks at k in `checks`
// (one entry a candidate); the others' arrive at theirs.
void shareLoopChecks(const dist::Group& group, std::vector<closure::LoopCheck>& checks);

}  // namespace hba::pyramid
