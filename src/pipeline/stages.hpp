#pragma once
// The stages of the method, in the order hierarchical_ba.cpp runs them. Each
// reads and moves run.poses and fills its part of run.report. Which process
// of an mpirun runs which stage is said in one place: kStages
// (hierarchical_ba.cpp).
#include "run.hpp"

namespace hba::pipeline {

// Loops and revisits verified and closed, priors met: run.poses becomes
// the hierarchy's start (docs/closure.md); each process verifies its share.
void closeLoops(Run& run);
// The paper's bottom-up plane BA over the pyramid of keyframes and the
// top-down pose graph, repeated until the poses settle (docs/pyramid.md);
// each process runs its share of a layer's windows.
void buildPyramid(Run& run);
// The self-check against the input's planes and the refinement over every
// scan (src/refine); each process solves with its share of the planes.
void refineMap(Run& run);
// With position priors: back onto them, bending over long stretches only.
void anchorOnPriors(Run& run);

}  // namespace hba::pipeline
