#pragma once
// The packing of pose-graph factors that the exchanges between the members
// of a group share (the windows' factors, the closures' loops).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "dist/bytes.hpp"
#include "hba/core/error.hpp"
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

}  // namespace hba::pyramid
