#pragma once
// Settings of the whole method: pyramid shape, BA settings per level, pose
// graph, iterations. Defaults are the paper's Table I where it gives one.
#include <cstddef>

#include "hba/ba/global_refinement.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/closure/revisits.hpp"
#include "hba/core/enum_names.hpp"
#include "hba/graph/information.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/graph/window_factors.hpp"

namespace hba {

// More worker threads than this is no machine hba runs on: the limit of
// hba -j, hba.optimize(threads=) and HbaSettings::threads.
inline constexpr int kMostThreads = 4096;

// How the top-down stage turns the pyramid into layer-1 poses.
enum class TopDownMode {
  PoseGraph,     // the paper's method: a pose graph over all layer-1 poses
  DirectAssign,  // the paper's ablation: copy upper poses down the pyramid
};

// How a BA window becomes pose-graph factors: one joint factor of its whole
// shape (the default), or pairs of its frames (adjacent: the paper's).
using graph::FactorPairs;

// The fields that the setting table declares (setting_table.cpp) get their
// defaults, ranges and help there, in one place (the table takes those of
// fields inside a module's struct, local, refinement, graph..., from that
// struct); the comments here say what the code does with them.
struct HbaSettings {
  int window{};  // w: frames per local window
  int stride{};  // s: frames between window starts (s < w: windows overlap)
  int layers{};  // pyramid layers including layer 1; 0 = the default rule

  double scan_voxel{};  // layer-1 scans are downsampled to this (m)
  // Keyframes (layer 2 and up) are downsampled to this (m). Coarser than the
  // scans: a keyframe merges ten overlapping scans, so the upper layers need
  // less density for the same accuracy, and save memory and time
  // (BENCHMARKS.md measures it).
  double keyframe_voxel{};
  // Each layer above multiplies the keyframe voxel by this: a keyframe of
  // layer i+1 covers `stride` times the path of one of layer i, so without
  // growth its point count (and memory, and BA time) would grow geometrically
  // with the layer. 1 = the same voxel on every layer.
  double keyframe_voxel_growth{};

  // Root voxel of the layer-1 windows (0 = local.planes.voxel_size). A
  // window of ten scans spans one second of odometry, which drifts by
  // centimetres, not metres: starting its coarse-to-fine association one
  // halving below the keyframe windows' saves a round (docs/pyramid.md).
  // Keyframe windows above span up to kilometres and keep
  // local.planes.voxel_size.
  double scan_window_voxel{};

  // Where a scan puts fewer than half a plane's minimum points in a voxel
  // of local.final_voxel_size, the windows' and the top BA's association
  // ends at a coarser voxel (final_voxel.hpp).
  bool adapt_final_voxel{};

  ba::BaSettings local;   // the windows of every layer
  ba::BaSettings global;  // the top layer's one BA (a looser plane test: finds large divergences)

  graph::InformationSettings information;
  TopDownMode top_down{};
  FactorPairs factor_pairs{};
  // The top-down pose graph's solver (its threads come from `threads`).
  graph::PoseGraphSettings graph;

  // The last stage: one sparse plane BA over every layer-1 frame at the
  // finest voxel, from the hierarchy's poses (docs/pyramid.md).
  bool refine{};
  ba::RefinementSettings refinement;
  // The refinement and the self-check hold every scan at once, downsampled
  // to this (m; 0 = as the windows' scans).
  double refine_scan_voxel{};
  // At most this many points (at refine_scan_voxel) are held at once: a
  // longer sequence is refined and checked in consecutive blocks that
  // overlap by a quarter. Peak memory grows with it (about 90 bytes a
  // point). Blocks lose the planes shared across them, so the budget is
  // generous.
  std::size_t refine_max_points{};
  // A sequence longer than one block is, after the blocks, refined
  // coarsely as a whole (docs/pyramid.md, "Long sequences"): consecutive
  // frames are tied into rigid groups (at least `group_min_frames`, at most
  // `group_max_count` groups), each group's scans merged with the blocks'
  // relative poses and downsampled to `group_voxel`, and one plane BA
  // places the groups.
  bool refine_groups{};
  std::size_t group_min_frames{};
  std::size_t group_max_count{};
  double group_voxel{};

  // The closure stage before the hierarchy (docs/closure.md): find places
  // the sequence comes back to by its poses, verify them with the plane BA
  // and close them, as loops from a file are.
  bool revisits{};
  closure::RevisitSettings revisit;

  // Worker threads of every parallel part, the pose graph's Ceres solve
  // included; 0 = as many as the process allows (hba -j, a
  // tbb::global_control, or the machine's cores). Results are identical run
  // to run for a given count. Not a setting of the table: the command line's
  // -j sets it. At most kMostThreads.
  int threads = 0;

  // Bottom-up + top-down rounds at most; they stop before when a round
  // moves no pose beyond the settle tolerances, or no less than the round
  // before (docs/pyramid.md).
  int outer_iterations{};
  double settle_translation_m{};
  double settle_rotation_deg{};

  // The settings each BA runs with: `information.point_sigma` scales every
  // motion prior into plane-cost units, and the refinement's slide check
  // measures against the windows' prior.
  ba::BaSettings localBa() const;
  ba::BaSettings globalBa() const;
  ba::RefinementSettings refinementBa() const;

  // The motion prior of every BA (windows, top, refinement) on or off.
  bool motionPrior() const { return local.motion_prior.enabled; }
  void setMotionPrior(bool on) {
    local.motion_prior.enabled = global.motion_prior.enabled = refinement.motion_prior.enabled = on;
  }

  // The defaults of every setting in the setting table (setting_table.hpp);
  // the other fields keep their own.
  HbaSettings();
};

// The voxel (m) that keyframes of `layer` (>= 2) are downsampled to.
double keyframeVoxel(const HbaSettings& settings, int layer);

}  // namespace hba

namespace hba {
template <>
struct EnumNames<TopDownMode> {
  static constexpr const char* what = "top-down mode";
  static constexpr EnumName<TopDownMode> names[] = {{TopDownMode::PoseGraph, "pose_graph"},
                                                    {TopDownMode::DirectAssign, "direct_assign"}};
};
}  // namespace hba
