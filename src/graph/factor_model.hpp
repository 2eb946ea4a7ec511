#pragma once
// The solver's interface to one factor kind. A new kind is one source file
// that implements FactorModel and defines modelOf() for its data struct
// (see position_prior_factor.cpp), plus its struct and modelOf()
// declaration in hba/graph/factors.hpp: the solver, the cost sum, the
// validation and the gauge rule go through this interface only.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <ceres/cost_function.h>

#include "gauge_anchors.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/factor_graph.hpp"

namespace hba::graph {

class NormalEquations;

// One Ceres cost of a factor and the nodes it depends on, as positions in
// the factor's nodes().
struct CostPiece {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<std::size_t> node_positions;
};

// Which PoseGraphSettings robust loss a factor gets.
enum class LossGroup { Window, Loop, Prior, None };

class FactorModel {
 public:
  virtual ~FactorModel() = default;

  // For messages and FactorGraph::count: "relative", "loop closure", ...
  virtual const char* name() const = 0;
  // The nodes the residual depends on, in the order of the Ceres cost's
  // parameter blocks (PoseBlocks under WorldPoseManifold's tangent).
  virtual std::vector<std::size_t> nodes() const = 0;
  virtual LossGroup lossGroup() const = 0;
  // What the factor fixes in the world frame, for the gauge rule.
  virtual GaugePin gaugePin() const { return {}; }

  // Throws hba::Error, its message starting with `label`, unless the factor
  // fits a graph of `num_poses` poses and its numbers are valid.
  virtual void validate(std::size_t num_poses, const std::string& label) const = 0;
  // e^T Omega e at `poses` (the factor is valid for them).
  virtual double cost(const std::vector<Pose>& poses) const = 0;
  // The whitened residual as a new Ceres cost; the caller takes ownership.
  virtual ceres::CostFunction* newCost() const = 0;
  // The same residual as costs whose squared norms sum to it, each over
  // the nodes its rows depend on: Ceres forms J^T J per cost, so a factor
  // whose rows each touch few nodes is cheaper in pieces. `whole`: one cost
  // (a robust loss must see the whole residual). By default newCost() over
  // every node.
  virtual std::vector<CostPiece> newCosts(bool whole) const;

  // Whether the factor adds its own terms to the normal equations in the
  // nodes' tangent (addNormalEquations) faster than they are formed from
  // newCost()'s Jacobian.
  virtual bool formsNormalEquations() const { return false; }
  // Adds e^T Omega e, J^T Omega e and J^T Omega J at `poses`, J = d e /
  // d (dt, dphi) of each node (formsNormalEquations() only).
  virtual void addNormalEquations(const std::vector<Pose>& poses, NormalEquations& system) const;
};

// Checks shared by the kinds; each throws hba::Error starting with `label`.
void checkNode(std::size_t node, std::size_t num_poses, const std::string& label);
void checkFinite(const Pose& measurement, const std::string& label);

}  // namespace hba::graph
