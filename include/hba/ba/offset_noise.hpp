#pragma once
// What a BA would gain by fitting its frames to noise alone, measured where
// poses act on planes: each frame's points on a plane, as one mean offset
// along the plane's normal. A pose can only move a frame's points on a plane
// together, so it is the spread of these offsets (not of single points)
// that a BA fits when there is nothing left to correct. Points of one frame
// share its errors (a surface seen from one place, a beam's range bias), so
// the offsets spread more than independent points would make them; this
// measure includes that.
#include <cstddef>
#include <vector>

#include "hba/ba/plane_problem.hpp"
#include "hba/core/pose.hpp"

namespace hba::ba {

// Each plane's frames' mean offsets along its normal at `poses`: their
// point-weighted sum of squares (sum over planes and frames of n_f o_f^2,
// the part of the plane cost between frames), and how many (plane, frame)
// pairs and planes it sums over.
struct FrameOffsets {
  double cost = 0.0;
  double pairs = 0.0;
  double planes = 0.0;
};
FrameOffsets frameOffsets(const PlaneProblem& problem, const std::vector<Pose>& poses);

// The expected plane-cost gain of fitting `frames` poses (6(frames - 1)
// degrees of freedom, one frame holding the gauge) to offsets that are
// noise: each degree of freedom takes one offset variance, estimated as the
// offsets' cost per remaining degree of freedom (pairs - planes - 6(frames -
// 1)). 0 when there are too few pairs to tell, or fewer than two frames.
double offsetNoiseGain(const FrameOffsets& offsets, std::size_t frames);

}  // namespace hba::ba
