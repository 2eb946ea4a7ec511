#pragma once
// Settings of the whole method: pyramid shape, BA settings per level, pose
// graph, iterations. Defaults are the paper's Table I where it gives one.
#include <cstddef>

#include "hba/ba/global_refinement.hpp"
#include "hba/ba/window_ba.hpp"
#include "hba/graph/information.hpp"
#include "hba/graph/window_factors.hpp"
#include "hba/pyramid/window_plan.hpp"  // maxLayerCount

namespace hba::pyramid {

// How the top-down stage turns the pyramid into layer-1 poses.
enum class TopDownMode {
  PoseGraph,     // the paper's method: a pose graph over all layer-1 poses
  DirectAssign,  // the paper's ablation: copy upper poses down the pyramid
};

// Which frame pairs of a BA window become pose-graph factors (adjacent by
// default, as in the paper's factor graph).
using graph::FactorPairs;

struct HbaSettings {
  int window = 10;  // w: frames per local window
  int stride = 5;   // s: frames between window starts (s < w: windows overlap)
  int layers = 0;   // pyramid layers including layer 1; 0 = the default rule

  double scan_voxel = 0.1;      // layer-1 scans are downsampled to this (m)
  // Keyframes (layer 2 and up) are downsampled to this (m). Coarser than the
  // scans: a keyframe merges ten overlapping scans, and at 0.2 m the upper
  // layers take ~3x less memory and ~25 % less total time for the same
  // accuracy (ATE within 10 % on simulated spinning and solid-state
  // sequences, same MME on hku1; BENCHMARKS.md).
  double keyframe_voxel = 0.2;
  // Each layer above multiplies the keyframe voxel by this: a keyframe of
  // layer i+1 covers `stride` times the path of one of layer i, so without
  // growth its point count (and memory, and BA time) would grow geometrically
  // with the layer. 1 = the same voxel on every layer.
  double keyframe_voxel_growth = 1.0;

  // Root voxel of the layer-1 windows (0 = local.planes.voxel_size). A
  // window of ten scans spans one second of odometry, which drifts by
  // centimetres, not metres: starting its coarse-to-fine association at 2 m
  // instead of 4 m saves one of three rounds (~10 % of layer 1's time) and
  // was as accurate on every benchmark sequence (docs/pyramid.md). Keyframe
  // windows above span up to kilometres and keep local.planes.voxel_size.
  double scan_window_voxel = 2.0;

  ba::BaSettings local;   // theta 0.05, V 4 m
  ba::BaSettings global;  // theta 0.1,  V 4 m (looser: finds large divergences)

  graph::InformationSettings information;
  TopDownMode top_down = TopDownMode::PoseGraph;
  FactorPairs factor_pairs = FactorPairs::Adjacent;
  int graph_max_iterations = 100;

  // The last stage: one sparse plane BA over every layer-1 frame at the
  // finest voxel, from the hierarchy's poses (docs/pyramid.md).
  bool refine = true;
  ba::RefinementSettings refinement;
  // The refinement and the self-check hold every scan at once, downsampled
  // to this (m; 0 = as the windows' scans).
  double refine_scan_voxel = 0.2;
  // At most this many points (at refine_scan_voxel) are held at once: a
  // longer sequence is refined and checked in consecutive blocks that
  // overlap by a quarter. Peak memory is about 90 bytes a point (400
  // simulated HDL-32 scans, 8.7 M points: 780 MB), so 20 M is about 2 GB.
  // Blocks lose the planes shared across them (hku1 in four blocks: MME
  // -3.008 instead of -3.037), so the budget is generous.
  std::size_t refine_max_points = 20'000'000;
  // A sequence longer than one block is, after the blocks, refined
  // coarsely as a whole (docs/pyramid.md, "Long sequences"): consecutive
  // frames are tied into rigid groups (at least `group_min_frames`, at most
  // `group_max_count` groups), each group's scans merged with the blocks'
  // relative poses and downsampled to `group_voxel`, and one plane BA
  // places the groups.
  bool refine_groups = true;
  std::size_t group_min_frames = 10;
  std::size_t group_max_count = 500;
  double group_voxel = 0.4;

  int outer_iterations = 1;          // bottom-up + top-down rounds at most
  double outer_tolerance_m = 1e-3;   // stop when no pose moved more than this
  double outer_tolerance_deg = 1e-3;

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

  HbaSettings() {
    global.planes.eigen_ratio = 0.1;
    // Coarse to fine (not in the paper): associations start at V = 4 m and
    // end at 1 m, see BENCHMARKS.md for why.
    local.final_voxel_size = 1.0;
    global.final_voxel_size = 1.0;
    // One association at the finest size after the coarse ones (4, 2, 1 m):
    // more rounds and a second outer iteration cost 2-4x the time for a few
    // percent of accuracy (BENCHMARKS.md).
    local.association_rounds = 1;
    global.association_rounds = 1;
  }
};

// The voxel (m) that keyframes of `layer` (>= 2) are downsampled to.
double keyframeVoxel(const HbaSettings& settings, int layer);

// The paper's optimal layer count l* = floor(1/2 log_s(3 N^2 (s^3 - s) n / w^3)),
// clamped to [1, the number of layers the sequence can hold].
int paperLayerCount(std::size_t frames, int window, int stride, int threads);
// The layer count hba uses when settings.layers == 0: the paper's formula
// with its own n = 8 threads, whatever this machine has, so that the same
// command builds the same pyramid (and gives the same poses) everywhere.
int defaultLayerCount(std::size_t frames, const HbaSettings& settings);

}  // namespace hba::pyramid
