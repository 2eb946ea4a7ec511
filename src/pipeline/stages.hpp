#pragma once
// The stages of one run, in the order runHierarchicalBa runs them
// (hierarchical_ba.cpp, which also says which process of a group runs
// which). Each takes what it reads and returns what it found; none reads
// another's report: the run's report is assembled from their outcomes.
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "closure_stage.hpp"
#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "pyramid/timed_clouds.hpp"
#include "refine/refinement.hpp"

namespace hba::pipeline {

// What every stage reads and none changes.
struct RunInput {
  RunInput(const pyramid::TimedClouds& scans_in, const HbaSettings& settings_in, const dist::Group& group_in)
      : scans(scans_in), settings(settings_in), group(group_in) {}

  const pyramid::TimedClouds& scans;  // layer 1: every scan read and downsampled once
  const HbaSettings& settings;        // the plan's: window size, final voxel and threads chosen
  const dist::Group& group;           // the processes of an mpirun (one, usually)
  int layers = 0;                     // the plan's
  // World points are floats: 4000 km from the origin (UTM) they are 0.25 m
  // apart. The stages work near the first input pose.
  std::vector<Pose> input;
  ClosureInputs closures;  // loops and priors to close, in the frame of `input`
};

// Loops and revisits verified and closed, priors met: where the hierarchy
// starts (docs/closure.md); each process verifies its share. Priors may put
// the start far from the input (UTM coordinates): the stages after work
// near its first pose, `shift` from the input's frame.
struct ClosedStart {
  ClosureOutcome closed;  // the start, the loops and priors kept, near `shift`
  std::vector<Pose> input;
  Vec3 shift = Vec3::Zero();
};
ClosedStart closeLoops(const RunInput& in);

// The paper's bottom-up plane BA over the pyramid of keyframes and the
// top-down pose graph, repeated until the poses settle (docs/pyramid.md);
// each process runs its share of a layer's windows.
struct PyramidOutcome {
  std::vector<Pose> poses;  // the hierarchy's: the last round's pose graph
  std::vector<LayerReport> layers;
  std::vector<IterationReport> iterations;
  std::vector<WindowRecord> windows;
  double seconds_read = 0.0, seconds_downsample = 0.0, seconds_voxelize = 0.0, seconds_solve = 0.0,
         seconds_keyframes = 0.0, seconds_graph = 0.0;
  std::string rounds_stopped;  // why the rounds stopped, and said with the figures
  std::string rounds_reason;
  std::size_t layer_one_points = 0;  // the points layer 1 held (its first round)
  std::size_t planes_found = 0;      // of every layer and round (none: the input is returned)
};
// `beside_last_graph`, when set: run beside the last round's pose graph
// (which keeps one thread), given the points layer 1 held.
PyramidOutcome buildPyramid(const RunInput& in, const ClosedStart& start,
                            const std::function<void(std::size_t layer_one_points)>& beside_last_graph = {});

// The self-check against the input's planes and the refinement over every
// scan (src/refine); each process solves with its share of the planes.
struct RefinedMap {
  refine::RefineOutcome outcome;
  // Its blocks held the priors to the end (no pass after them moved the
  // frames without the priors): no re-anchoring is due.
  bool priors_held = false;
};
RefinedMap refineMap(const RunInput& in, const ClosedStart& start, const PyramidOutcome& pyramid,
                     refine::PreparedStart* prepared = nullptr);
// The refinement's first block and its input's planes, which need no pose
// of the pyramid's (refine::prepareStart).
refine::PreparedStart prepareRefinement(const RunInput& in, const ClosedStart& start,
                                        std::size_t layer_one_points);

// With position priors the refinement did not hold: back onto them,
// bending over long stretches only.
struct Anchoring {
  bool ran = false;
  std::vector<Pose> poses;
  double move_m = 0.0;             // the largest move of a pose
  std::size_t priors_dropped = 0;  // kept by the closures, contradicted by the final shape
};
Anchoring anchorOnPriors(const RunInput& in, const ClosedStart& start, const RefinedMap& refined);

// Logs how long each stage took, in the order they ran.
void logStageTimes(const std::vector<std::pair<std::string, double>>& stage_seconds);

}  // namespace hba::pipeline
