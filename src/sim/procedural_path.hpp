#pragma once
// The closed curve a procedural trajectory drives, and walking it from any
// point in either direction: several sessions drive stretches of one curve.
#include <cstddef>

#include "closed_curve.hpp"
#include "hba/sim/trajectory.hpp"

namespace hba::sim {

// The shape's loop, one lap sized from `config.frames` (as makeTrajectory does).
ClosedCurve pathCurve(const TrajectoryConfig& config);

// `frames` positions `step` metres apart from arc length `start`, against
// the curve's direction if `reverse`; headings along the direction of travel.
PlanarPath walkCurve(const ClosedCurve& curve, double start, double step, std::size_t frames, bool reverse);

}  // namespace hba::sim
