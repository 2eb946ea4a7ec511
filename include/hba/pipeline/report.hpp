#pragma once
// What a run of the method reports (report.json's "hba" part; docs/cli.md
// lists its keys): plain data, filled by the stages.
#include <cstddef>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/pipeline/final_voxel.hpp"
#include "hba/pipeline/window_size.hpp"
#include "hba/pyramid/layer_report.hpp"
#include "hba/refine/report.hpp"

namespace hba::pipeline {

// The pyramid's own reports (layer_report.hpp).
using pyramid::IterationReport;
using pyramid::LayerReport;
using pyramid::WindowRecord;

// The last stage's reports (hba/refine/report.hpp).
using refine::ConsistencyReport;
using refine::GroupRefinementReport;
using refine::RefinementReport;

// One loop closure candidate and what became of it.
struct LoopReport {
  std::size_t from = 0;
  std::size_t to = 0;
  std::string source;     // "file" or "revisit"
  bool verified = false;  // the plane BA supports it
  bool used = false;      // verified and consistent with the rest: in the pose graphs
  std::string reason;     // why not verified, or why dropped
  std::size_t shared_planes = 0;
  double overlap = 0.0;
  double rms_m = 0.0;
  double correction_m = 0.0;  // of the guess, by the verification
  double correction_deg = 0.0;
};

// The closure stage before the hierarchy (docs/closure.md).
struct ClosureReport {
  bool ran = false;
  bool revisits_searched = false;
  std::size_t loops_given = 0;         // from the caller (a loop file)
  std::size_t revisit_candidates = 0;  // found by the poses (also counted when not searched)
  std::size_t verified = 0;
  std::size_t rejected_by_planes = 0;
  std::size_t dropped_as_inconsistent = 0;  // verified, but the other loops and priors disagree
  std::size_t loops_used = 0;
  std::size_t priors_given = 0;
  std::size_t priors_dropped = 0;  // disagree with the rest beyond their sigma
  std::size_t priors_used = 0;
  double largest_move_m = 0.0;  // of a pose, by the closure graph
  // Every loop and prior used already held at the input poses: the graph
  // was not solved and the start is the input (a closed map stays put).
  bool held_at_input = false;
  // With priors: how far the final re-anchoring on them moved a pose.
  double anchoring_move_m = 0.0;
  std::size_t anchoring_priors_dropped = 0;  // kept by the closure graph, contradicted by the final shape
  std::vector<LoopReport> loops;
  double seconds = 0.0;
};

struct HbaReport {
  int layers = 0;
  WindowSize windows;      // the layer-1 windows used (window_size.hpp)
  FinalVoxel final_voxel;  // where the windows' association ended (final_voxel.hpp)
  int threads = 0;         // that every parallel part ran on, the pose graph included
  int processes = 1;       // the group's members the windows were spread over (mpirun's ranks)
  std::size_t frames = 0;
  std::vector<LayerReport> layer_reports;
  std::vector<IterationReport> iterations;
  std::vector<WindowRecord> window_records;  // every window of every layer and round
  ClosureReport closure;
  RefinementReport refinement;
  ConsistencyReport consistency;
  // Wall time by stage. Reading and downsampling run together in parallel,
  // as do voxelization and LM; their wall time is split in proportion to
  // the thread time each part took.
  double seconds_read = 0.0;        // reading scans and stored keyframes
  double seconds_downsample = 0.0;  // downsampling layer-1 scans
  double seconds_voxelize = 0.0;    // plane extraction and point clusters, all BAs
  double seconds_solve = 0.0;       // LM of all BAs
  double seconds_keyframes = 0.0;   // building keyframe clouds
  double seconds_graph = 0.0;       // pose graph solves
  double seconds_total = 0.0;
  // Why the outer iterations stopped: "iteration limit" (--iterations; the
  // default is one pass), "poses settled" (the last moved no pose beyond the
  // settle tolerances) or "moves stopped shrinking"; and as a sentence with
  // the figures ("settled after 3 rounds: largest move ...").
  std::string rounds_stopped = "iteration limit";
  std::string rounds_reason;
  // Final poses against the input (the iterations' figures are the
  // hierarchy's alone).
  double largest_translation_update = 0.0;  // m
  double largest_rotation_update = 0.0;     // degrees
  std::vector<std::string> warnings;
};

}  // namespace hba::pipeline
