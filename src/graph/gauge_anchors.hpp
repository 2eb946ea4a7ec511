#pragma once
// Which nodes hold the gauge. A pose graph of relative and loop factors is
// invariant to one rigid motion per connected component; priors may remove
// that freedom, or only its translation. See "The gauge" in docs/graph.md.
#include <cstddef>
#include <vector>

#include "hba/core/types.hpp"
#include "hba/graph/factors.hpp"

namespace hba::graph {

// What one factor fixes in the world frame, counted only when its
// information constrains every direction it measures.
enum class PinKind { None, Position, Pose };
struct GaugePin {
  PinKind kind = PinKind::None;
  Vec3 position = Vec3::Zero();  // the pinned world position (Position only)
};

// One factor as the gauge rule sees it: the nodes it joins into one
// component (one node for a prior), and what it pins.
struct GaugeInput {
  std::vector<std::size_t> nodes;
  GaugePin pin;
};

enum class GaugeHold {
  Pose,         // the node is held entirely
  Orientation,  // only its rotation is held; its position is solved
};

struct GaugeAnchor {
  std::size_t node = 0;
  GaugeHold hold = GaugeHold::Pose;
  bool operator==(const GaugeAnchor& other) const { return node == other.node && hold == other.hold; }
};

// Root-sum-square distance of `points` from their best-fitting line: the
// lever arm that position priors give against a rotation of the component
// about that line (0 for fewer than three points, or collinear ones).
double spreadOffLine(const std::vector<Vec3>& points);

// One anchor per connected component that needs one, ascending by node:
// none when the component has a Pose pin or Position pins spread at least
// `min_prior_spread` off their line; the smallest node's Orientation when it
// has other Position pins; the smallest node's whole Pose otherwise. Node
// indices must already be valid.
std::vector<GaugeAnchor> componentAnchors(std::size_t num_nodes, const std::vector<GaugeInput>& factors,
                                          double min_prior_spread);

// The rule for relative factors alone: the smallest node of every component
// that has a factor, ascending.
std::vector<std::size_t> gaugeAnchors(std::size_t num_nodes, const std::vector<RelativePoseFactor>& factors);

}  // namespace hba::graph
