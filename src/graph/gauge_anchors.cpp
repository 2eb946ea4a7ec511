#include "gauge_anchors.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Eigenvalues>

namespace hba::graph {
namespace {

// Union-find whose representative is always the smallest index of its set.
class SmallestRootSets {
 public:
  explicit SmallestRootSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t root(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    const std::size_t ra = root(a);
    const std::size_t rb = root(b);
    if (ra < rb) parent_[rb] = ra;
    if (rb < ra) parent_[ra] = rb;
  }

 private:
  std::vector<std::size_t> parent_;
};

// The priors that landed in one component.
struct ComponentPins {
  bool pose = false;
  std::vector<Vec3> positions;
};

}  // namespace

double spreadOffLine(const std::vector<Vec3>& points) {
  if (points.size() < 3) return 0.0;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Mat3 scatter = Mat3::Zero();
  for (const Vec3& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  // The two smaller principal moments are the squared distances off the
  // principal axis, summed over the points.
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(scatter, Eigen::EigenvaluesOnly);
  const Vec3& moments = eigen.eigenvalues();  // ascending
  return std::sqrt(std::max(moments[0] + moments[1], 0.0));
}

std::vector<GaugeAnchor> componentAnchors(std::size_t num_nodes, const std::vector<GaugeInput>& factors,
                                          double min_prior_spread) {
  SmallestRootSets sets(num_nodes);
  std::vector<bool> touched(num_nodes, false);
  for (const GaugeInput& f : factors) {
    for (const std::size_t node : f.nodes) {
      sets.join(f.nodes.front(), node);
      touched[node] = true;
    }
  }
  std::vector<ComponentPins> pins(num_nodes);
  for (const GaugeInput& f : factors) {
    if (f.nodes.empty() || f.pin.kind == PinKind::None) continue;
    ComponentPins& component = pins[sets.root(f.nodes.front())];
    if (f.pin.kind == PinKind::Pose) component.pose = true;
    if (f.pin.kind == PinKind::Position) component.positions.push_back(f.pin.position);
  }
  std::vector<GaugeAnchor> anchors;
  for (std::size_t i = 0; i < num_nodes; ++i) {
    if (!touched[i] || sets.root(i) != i) continue;
    const ComponentPins& component = pins[i];
    if (component.pose || spreadOffLine(component.positions) >= min_prior_spread) continue;
    const GaugeHold hold = component.positions.empty() ? GaugeHold::Pose : GaugeHold::Orientation;
    anchors.push_back({i, hold});
  }
  return anchors;
}

std::vector<std::size_t> gaugeAnchors(std::size_t num_nodes, const std::vector<RelativePoseFactor>& factors) {
  std::vector<GaugeInput> inputs;
  inputs.reserve(factors.size());
  for (const RelativePoseFactor& f : factors) inputs.push_back({{f.from, f.to}, {}});
  std::vector<std::size_t> nodes;
  // Without pins every anchor holds a whole pose; the spread never matters.
  for (const GaugeAnchor& anchor : componentAnchors(num_nodes, inputs, 1.0)) {
    nodes.push_back(anchor.node);
  }
  return nodes;
}

}  // namespace hba::graph
