#pragma once
// The whole method: bottom-up hierarchical BA over a pyramid of keyframes,
// then a top-down pose graph (or direct assignment) back to every scan,
// repeated until the poses settle. See docs/pyramid.md.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/closure_inputs.hpp"
#include "hba/pipeline/plan.hpp"
#include "hba/pipeline/report.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

struct HbaResult {
  std::vector<Pose> poses;  // optimized layer-1 poses, same order as the input
  // The poses the paper's method left (the top-down pose graph of the last
  // round), before the refinement: what the hierarchy alone reached.
  std::vector<Pose> hierarchy_poses;
  HbaReport report;
  // The scans as the run read them, at settings.scan_voxel, kept on disk (a
  // private folder in $TMPDIR, removed with the last copy of this pointer):
  // a picture or map afterwards need not parse and downsample them again.
  // Reads through to the caller's `scans`, which must outlive it. Null for a
  // single scan (nothing kept).
  std::shared_ptr<const io::ScanSource> scans;
};

// `scans` as read (sensor frame, full density: a dataset's or scans in
// memory); they are downsampled to settings.scan_voxel as they are loaded,
// and only read. Throws hba::Error if the pose count differs from the scan
// count or the settings are inconsistent, and what `scans` throws.
// `closures` (loops to verify, position priors) are closed before the
// hierarchy runs and kept in its pose graph; with priors that fix the frame
// no pose is held.
// With `group` (the processes of an mpirun), each layer's windows are spread
// over its members, which must all call this with the same input; each
// reads only the scans of its windows there, and all get the same poses,
// those of one process. The closures and the refinement are shared the
// same way; the anchoring on priors runs in the first member only
// (runStages in src/pipeline/hierarchical_ba.cpp says which stage runs where).
HbaResult runHierarchicalBa(const io::ScanSource& scans, const std::vector<Pose>& initial,
                            const HbaSettings& settings, const ClosureInputs& closures = {},
                            const dist::Group& group = dist::singleProcess());
// The same, by a plan worked out before (planRun over the same `scans`):
// the memory check and the run then see one plan.
HbaResult runHierarchicalBa(const io::ScanSource& scans, const std::vector<Pose>& initial, const Plan& plan,
                            const ClosureInputs& closures = {},
                            const dist::Group& group = dist::singleProcess());

}  // namespace hba::pipeline
