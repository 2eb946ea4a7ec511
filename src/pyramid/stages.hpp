#pragma once
// The stages of the method, in the order hierarchical_ba.cpp runs them. Each
// reads and moves run.poses and fills its part of run.report.
#include "run.hpp"

namespace hba::pyramid {

// Loops and revisits verified and closed, priors met: run.poses becomes
// the hierarchy's start (docs/closure.md). Every process.
void closeLoops(Run& run);
// The paper's bottom-up plane BA over the pyramid of keyframes and the
// top-down pose graph, repeated until the poses settle (docs/pyramid.md).
// Every process: each runs its share of a layer's windows.
void buildPyramid(Run& run);
// The self-check against the input's planes and the refinement over every
// scan (src/refine). The first process.
void refineMap(Run& run);
// With position priors: back onto them, bending over long stretches only.
// The first process.
void anchorOnPriors(Run& run);

}  // namespace hba::pyramid
