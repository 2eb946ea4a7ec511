#pragma once
// Plane bundle adjustment of a small set of scans (a window): the public entry
// point of the BA core. See docs/ba.md for the method and its conventions.
//
// Pose perturbation convention (used by the Hessian below): frame i's pose is
// updated as R_i <- Exp(dphi_i) R_i, t_i <- t_i + dt_i (world frame), and the
// 6 coordinates of frame i are ordered (dt_i, dphi_i), at rows 6i .. 6i+5.
//
// Cost: sum over plane features of N_p * lambda_min(C_p), i.e. the sum of the
// squared point-to-plane distances of all plane points.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hba/ba/motion_prior.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::ba {

// The plane extraction settings live with the voxel map (same fields).
using PlaneSettings = voxel::PlaneSettings;

struct BaSettings {
  PlaneSettings planes;
  int max_iterations = 10;  // LM iterations per association round
  // Associations (voxel planes rebuilt from the updated poses) at the finest
  // voxel size; coarse-to-fine rounds below come on top of these.
  int association_rounds = 1;
  // Coarse to fine: the first association uses planes.voxel_size, each later
  // one halves it, down to this size (m); rounds stop only once it is reached
  // and the cost has settled (or association_rounds is spent beyond that).
  // Large voxels catch large divergences, small ones give crisp local planes
  // and the Hessian is taken at the finest association. 0 or >= voxel_size:
  // one size for all rounds (the paper).
  double final_voxel_size = 1.0;
  double reject_ratio = 0.05;             // drop this fraction of planes, worst residuals first
  double relative_cost_tolerance = 1e-4;  // stop when the cost settles
  // Neighbouring frames are held weakly at their input relative pose.
  MotionPriorSettings motion_prior;
  // Trust check: the planes found at the input poses (finest voxel) must not
  // get blurrier at the result; a result that fails keeps the input poses.
  // One that fails after coarser rounds is first solved again on those
  // planes from the input (BaResult::solved_again_at_input).
  bool check_fixed_map = true;
  // Also not trusted (with check_fixed_map and the prior on): neighbouring
  // frames whose relative pose moved by more than this many prior sigmas
  // (0.75 m between frames 0.5 m apart): frames slid along a direction the
  // planes do not hold, or pulled into a wrong alignment. Smaller, a real
  // odometry glitch (a jump of half a metre) would never be corrected.
  // 0 = off.
  double slide_sigmas = 5.0;
  // Settle check (with check_fixed_map): a result that lowers the cost of
  // the planes found at the input poses by no more than this many times
  // what fitting the frames to noise would gain (offset_noise.hpp) keeps
  // the input poses: the window has nothing to correct. Without it, windows
  // of a converged map move to an optimum of their own, seen from a few
  // nearby places only. Measured at a converged map, windows gain 1-7 times
  // that (18 on sparse scans); from drifting odometry 6 to thousands
  // (docs/pyramid.md). 0 = off.
  double significant_gain = 8.0;
};

struct BaResult {
  std::vector<Pose> poses;  // optimized, same count and order as the input
  // Hessian of the cost (planes and motion prior) at the solution, 6K x 6K in the convention above
  // (not gauge-fixed: the caller chooses which frame to fix).
  Eigen::MatrixXd hessian;
  // Plane costs (without the motion prior's).
  double initial_cost = 0.0;  // at the initial poses and first association
  double final_cost = 0.0;    // at the solution and last association
  // The last association's cost at the initial poses: compare with
  // final_cost for a like-for-like improvement (same planes, same points).
  double last_association_initial_cost = 0.0;
  // The trust check: cost of the planes found at the input poses, at the
  // input and at the solution; `trusted` is false when the solution made
  // them blurrier or slid neighbouring frames apart (slide_sigmas), and
  // then `poses` are the input poses.
  double fixed_map_cost_initial = 0.0;
  double fixed_map_cost_final = 0.0;
  bool trusted = true;
  // Settle check: the result gained no more than significant_gain times
  // fitting noise, and `poses` are the input poses; the gain in units of
  // fitting noise (measured whenever the trust check passed; 0 otherwise).
  bool settled = false;
  double gain_over_noise = 0.0;
  // Coarse to fine, the last round's result failed the trust check (the
  // input's finest planes blurrier, or frames slid apart): those planes
  // were solved again from the input, and that result, when it passed the
  // trust check, was judged instead (a converged map, which coarser planes
  // pull off); or settled there, where one Gauss-Newton step from the input
  // predicted no more gain than the settle check allows.
  bool solved_again_at_input = false;
  int rounds = 0;              // association rounds run
  std::size_t num_planes = 0;  // plane features used in the last round
  std::size_t num_plane_points = 0;
  int iterations = 0;  // LM iterations over all rounds
  // Per plane of the last round: RMS point-to-plane distance (m) before and
  // after, in the same order.
  std::vector<double> plane_rms_initial;
  std::vector<double> plane_rms_final;
  // Per frame: indices (into that frame's input cloud) of the points that
  // belong to plane features in the last round, sorted. Keyframes are built
  // from these.
  std::vector<std::vector<std::uint32_t>> plane_point_indices;
  // Thread time of this call: finding planes (voxelization, clusters) and
  // solving (LM), for the stage times of a report.
  double seconds_associate = 0.0;
  double seconds_solve = 0.0;
};

// Optimizes the poses of `scans` (sensor frame, already downsampled) starting
// from `initial`. Frame 0 is held fixed (gauge). `path_m[k]` is the path (m)
// between frames k and k+1 for the motion prior (empty: straight distances).
// Thread-safe and deterministic for any thread count. Scans are only read.
BaResult optimizeWindow(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
                        const BaSettings& settings, const std::vector<double>& path_m = {});

}  // namespace hba::ba
